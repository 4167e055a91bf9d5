// The terrasynth program minus main(): the command registry and the top-level error handling.
#include <algorithm>
#include <cstdio>
#include <vector>

#include "command_registry.h"
#include "terrasynth/guard.h"

namespace terrasynth::cli {
namespace {
struct Entry {
    std::string name;
    int order;
    CommandSetup setup;
    int bad_flag_exit;
};
std::vector<Entry>& registry() {
    static std::vector<Entry> entries;
    return entries;
}
}  // namespace

CommandRegistration::CommandRegistration(const char* name, int order, CommandSetup setup, int bad_flag_exit) {
    registry().push_back({name, order, std::move(setup), bad_flag_exit});
}

int& exitCode() {
    static int code = 0;
    return code;
}

void fail(const std::string& command, const std::string& message) {
    std::fprintf(stderr, "terrasynth %s: %s\n", command.c_str(), message.c_str());
    exitCode() = 1;
}

void warn(const std::string& message) { std::fprintf(stderr, "terrasynth: warning: %s\n", message.c_str()); }

bool& parseOnly() {
    static bool only = false;
    return only;
}

void setAction(CLI::App* command, std::function<void()> action) {
    command->callback([action = std::move(action)] {
        if (!parseOnly()) action();
    });
}

std::string jsonText(const nlohmann::json& value, int indent) {
    return value.dump(indent, ' ', /*ensure_ascii=*/false, nlohmann::json::error_handler_t::replace);
}

namespace {

// "terrasynth db build": the program and the subcommands parsed so far.
std::string commandPath(CLI::App& app) {
    std::string path = "terrasynth";
    for (CLI::App* current = &app;;) {
        const std::vector<CLI::App*> parsed = current->get_subcommands();
        if (parsed.empty()) return path;
        current = parsed.front();
        path += " " + current->get_name();
    }
}

// CLI11 reports a misspelt command as "A subcommand is required"; name the word and the commands.
std::string unknownCommand(CLI::App& app, int argc, const char* const* argv) {
    CLI::App* current = &app;
    std::string path = "terrasynth";
    for (int i = 1; i < argc; ++i) {
        const std::string word = argv[i];
        if (word.empty() || word[0] == '-') return "";
        const std::vector<CLI::App*> known = current->get_subcommands([](CLI::App*) { return true; });
        CLI::App* next = nullptr;
        std::string names;
        for (CLI::App* sub : known) {
            if (sub->get_name() == word) next = sub;
            names += (names.empty() ? "" : ", ") + sub->get_name();
        }
        if (!next) {
            if (current->get_require_subcommand_min() == 0 || known.empty()) return "";
            return path + ": unknown command \"" + word + "\" (commands: " + names + ")";
        }
        current = next;
        path += " " + word;
    }
    return "";
}

// The exit code for flags that do not parse: that of the command being parsed (1 before one is).
int badFlagExit(CLI::App& app, const std::vector<Entry>& entries) {
    const std::vector<CLI::App*> parsed = app.get_subcommands();
    if (parsed.empty()) return 1;
    for (const Entry& e : entries)
        if (e.name == parsed.front()->get_name()) return e.bad_flag_exit;
    return 1;
}

}  // namespace

int runCli(int argc, const char* const* argv) {
    exitCode() = 0;
    CLI::App app{"terrasynth: terrain synthesis by example (Gain et al. 2015, Bradbury et al. 2014)"};
    app.require_subcommand(1);
    auto entries = registry();
    std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return a.order < b.order; });
    for (const Entry& e : entries) e.setup(app);
    if (const std::string unknown = unknownCommand(app, argc, argv); !unknown.empty()) {
        std::fprintf(stderr, "%s\nRun with --help for more information.\n", unknown.c_str());
        return 1;
    }
    // The commands run inside parse(); anything they throw (out of memory, ...) ends here as a
    // message naming the command, and exit code 1.
    return terrasynth::invokeGuarded(
        [&] {
            try {
                app.parse(argc, argv);
            } catch (const CLI::CallForHelp& e) {
                return app.exit(e);
            } catch (const CLI::CallForAllHelp& e) {
                return app.exit(e);
            } catch (const CLI::ParseError& e) {
                std::fprintf(stderr, "%s: %s\nRun with --help for more information.\n", commandPath(app).c_str(), e.what());
                return badFlagExit(app, entries);
            }
            return exitCode();
        },
        [&](const std::string& why) {
            std::fprintf(stderr, "%s: %s\n", commandPath(app).c_str(), why.c_str());
            return 1;
        });
}

}  // namespace terrasynth::cli
