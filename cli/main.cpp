// terrasynth: the command-line tool (cli_app.cpp has the commands and their error handling).
#include "command_registry.h"
#include "terrasynth/guard.h"

int main(int argc, char** argv) {
    return terrasynth::runGuarded("terrasynth", [&] { return terrasynth::cli::runCli(argc, argv); });
}
