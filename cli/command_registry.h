// Subcommands register themselves at static-initialisation time:
//   static const CommandRegistration kStats{"stats", 40, addStatsCommand};
// `order` sorts the help listing. The setup function adds a CLI11 subcommand and sets its callback;
// callbacks report failure by setting the exit code (see exitCode()) rather than throwing.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>

namespace terrasynth::cli {

using CommandSetup = std::function<void(CLI::App& app)>;

struct CommandRegistration {
    CommandRegistration(const char* name, int order, CommandSetup setup);
};

// Exit code set by the command that ran; 0 when it succeeded.
int& exitCode();

// Prints "terrasynth <command>: <message>" to stderr and sets the exit code to 1.
void fail(const std::string& command, const std::string& message);
// Prints "terrasynth: warning: <message>" to stderr (recoverable surprises, e.g. a stale sidecar).
void warn(const std::string& message);

}  // namespace terrasynth::cli
