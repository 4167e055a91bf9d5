#include <algorithm>
#include <cstdio>
#include <vector>

#include "command_registry.h"

namespace terrasynth::cli {
namespace {
struct Entry {
    std::string name;
    int order;
    CommandSetup setup;
};
std::vector<Entry>& registry() {
    static std::vector<Entry> entries;
    return entries;
}
}  // namespace

CommandRegistration::CommandRegistration(const char* name, int order, CommandSetup setup) {
    registry().push_back({name, order, std::move(setup)});
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

}  // namespace terrasynth::cli

int main(int argc, char** argv) {
    using namespace terrasynth::cli;
    CLI::App app{"terrasynth: terrain synthesis by example (Gain et al. 2015, Bradbury et al. 2014)"};
    app.require_subcommand(1);
    auto entries = registry();
    std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return a.order < b.order; });
    for (const Entry& e : entries) e.setup(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    }
    return exitCode();
}
