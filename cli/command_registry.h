// Subcommands register themselves at static-initialisation time:
//   static const CommandRegistration kStats{"stats", 40, addStatsCommand};
// `order` sorts the help listing. The setup function adds a CLI11 subcommand and gives it its action
// (setAction); actions report failure by setting the exit code (see exitCode()) rather than throwing.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

namespace terrasynth::cli {

using CommandSetup = std::function<void(CLI::App& app)>;

// `bad_flag_exit`: the exit code when the command's flags do not parse (a value out of range, NaN,
// an unknown flag): 1, or 2 for commands whose docs promise 2 for bad input (bake, docs/bake.md).
struct CommandRegistration {
    CommandRegistration(const char* name, int order, CommandSetup setup, int bad_flag_exit = 1);
};

// Exit code set by the command that ran; 0 when it succeeded.
int& exitCode();

// What a command does once its arguments parsed. Skipped while parseOnly() is set.
void setAction(CLI::App* command, std::function<void()> action);
// Parse the arguments only, running no command (the flag-parser fuzz target sets it).
bool& parseOnly();

// The whole program: builds the commands, parses argv, runs the chosen command. Returns the exit
// code: 0, or 1 with a message naming the command on stderr (bad flags, failed command, and any
// exception, e.g. out of memory); bad flags of a command registered with bad_flag_exit 2 give 2.
int runCli(int argc, const char* const* argv);

// Prints "terrasynth <command>: <message>" to stderr and sets the exit code to 1.
void fail(const std::string& command, const std::string& message);
// Prints "terrasynth: warning: <message>" to stderr (recoverable surprises, e.g. a stale sidecar).
void warn(const std::string& message);

// JSON text for printing or writing; bytes that are not UTF-8 (a file name in a legacy encoding)
// become U+FFFD instead of an exception. indent < 0: compact.
std::string jsonText(const nlohmann::json& value, int indent = -1);

}  // namespace terrasynth::cli
