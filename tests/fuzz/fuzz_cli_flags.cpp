// Fuzz target: the command line's flag parsing (CLI11 with every terrasynth command, the unknown
// command check, option types, ranges and delimiters) with the commands themselves not run
// (parseOnly). Input: the arguments, separated by newlines or NUL bytes.
#include <string>
#include <vector>

#include "command_registry.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    terrasynth::cli::parseOnly() = true;
    std::vector<std::string> words{"terrasynth"};
    std::string word;
    for (size_t i = 0; i < size && words.size() < 64; ++i) {
        const char c = static_cast<char>(data[i]);
        if (c == '\n' || c == '\0') {
            words.push_back(word);
            word.clear();
        } else {
            word += c;
        }
    }
    if (!word.empty()) words.push_back(word);
    std::vector<const char*> argv;
    for (const std::string& w : words) argv.push_back(w.c_str());
    const int code = terrasynth::cli::runCli(static_cast<int>(argv.size()), argv.data());
    if (code != 0 && code != 1) __builtin_trap();  // every failure is exit 1 with a message
    return 0;
}
