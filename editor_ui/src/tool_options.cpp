#include "tool_options.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "terrasynth/status.h"

namespace terrasynth::editor {

ToolOptions::Option& ToolOptions::make(const std::string& key, Option::Kind kind) {
    Option fresh;
    fresh.kind = kind;
    auto it = options_.try_emplace(key, std::move(fresh)).first;
    TERRASYNTH_REQUIRE(it->second.kind == kind, ("tool option '" + key + "' asked for as two kinds").c_str());
    return it->second;
}

ToolOptions::Option& ToolOptions::existing(const std::string& key, Option::Kind kind) {
    const auto it = options_.find(key);
    TERRASYNTH_REQUIRE(it != options_.end() && it->second.kind == kind, ("no tool option '" + key + "' of that kind").c_str());
    return it->second;
}

float& ToolOptions::number(const std::string& key, float initial) {
    const bool made = !options_.count(key);
    Option& o = make(key, Option::Kind::Number);
    if (made) o.number = initial;
    return o.number;
}

bool& ToolOptions::flag(const std::string& key, bool initial) {
    const bool made = !options_.count(key);
    Option& o = make(key, Option::Kind::Flag);
    if (made) o.flag = initial;
    return o.flag;
}

int& ToolOptions::choice(const std::string& key, int initial, std::function<std::vector<std::string>()> names,
                         std::string what) {
    const bool made = !options_.count(key);
    Option& o = make(key, Option::Kind::Choice);
    if (made) {
        o.index = initial;
        o.names = std::move(names);
        o.what = std::move(what);
    }
    return o.index;
}

float& ToolOptions::number(const std::string& key) { return existing(key, Option::Kind::Number).number; }

Status ToolOptions::set(const std::string& key, const std::string& value) {
    const auto it = options_.find(key);
    if (it == options_.end()) return Status::error("unknown option '" + key + "'");
    Option& o = it->second;
    switch (o.kind) {
        case Option::Kind::Number: {
            char* end = nullptr;
            const double v = std::strtod(value.c_str(), &end);
            if (end == value.c_str() || *end || !std::isfinite(v)) return Status::error("'" + value + "' is not a number");
            o.number = static_cast<float>(v);
            return Status::ok();
        }
        case Option::Kind::Flag:
            if (value == "1" || value == "true" || value == "on") o.flag = true;
            else if (value == "0" || value == "false" || value == "off") o.flag = false;
            else return Status::error("'" + value + "' is not 0 or 1");
            return Status::ok();
        case Option::Kind::Choice: {
            const std::vector<std::string> names = o.names();
            const auto found = std::find(names.begin(), names.end(), value);
            if (found != names.end()) {
                o.index = static_cast<int>(found - names.begin());
                return Status::ok();
            }
            std::string list;
            for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
            return Status::error("unknown " + o.what + " '" + value + "' (" + list + ")");
        }
    }
    return Status::error("unknown option '" + key + "'");
}

}  // namespace terrasynth::editor
