// Private: the tools' options, keyed by the names scripts use (`set point.raise 400`).
//
// A tool asks for its options when it is made and keeps the references: the options panel edits the
// values in place and `set KEY VALUE` goes through set(). Tools that ask for the same key share one
// value (paint and freeze share brush.radius, as one brush). Main (UI) thread only.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "terrasynth/status.h"

namespace terrasynth::editor {

class ToolOptions {
public:
    ToolOptions() = default;
    ToolOptions(const ToolOptions&) = delete;
    ToolOptions& operator=(const ToolOptions&) = delete;

    // The option `key`, made with `initial` on the first call; later calls return the same value.
    // Precondition: a key keeps its kind (a number stays a number).
    float& number(const std::string& key, float initial);
    bool& flag(const std::string& key, bool initial);
    // One of `names()` (asked when set() parses a value, so the list may change: a database's
    // types); the value is its index. `what` names a choice in messages ("preset").
    int& choice(const std::string& key, int initial, std::function<std::vector<std::string>()> names, std::string what);
    // A number some tool made. Precondition: it exists.
    float& number(const std::string& key);

    // Parses `value` for `key`: numbers in any strtod form, flags 1/0, true/false, on/off, choices by
    // name. Errors: "unknown option 'KEY'", "'VALUE' is not a number", ... (nothing changes).
    Status set(const std::string& key, const std::string& value);

private:
    struct Option {
        enum class Kind { Number, Flag, Choice } kind;
        float number = 0.0f;
        bool flag = false;
        int index = 0;
        std::function<std::vector<std::string>()> names;
        std::string what;
    };
    Option& make(const std::string& key, Option::Kind kind);
    Option& existing(const std::string& key, Option::Kind kind);

    std::map<std::string, Option> options_;  // node-based: references stay valid
};

}  // namespace terrasynth::editor
