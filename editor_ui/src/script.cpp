// Parsing --script files (terrasynth_editor/script.h).
#include "terrasynth_editor/script.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <sstream>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "terrasynth/heightfield_io.h"

namespace terrasynth::editor {
namespace {

// Argument shape of each command: how many numbers lead, how many arguments in all.
struct Shape {
    int min_args, max_args;
    int numeric;  // the first `numeric` arguments must be numbers (-1: every argument given)
    const char* usage;
};

const std::map<std::string, Shape>& shapes() {
    static const std::map<std::string, Shape> s = {
        {"wait", {1, 1, 1, "FRAMES"}},
        {"sleep", {1, 1, 1, "MS"}},
        {"settle", {0, 1, 1, "[TIMEOUT_S]"}},
        {"view", {4, 6, 0, "aerial X Y WIDTH_M | free X Y DISTANCE_M HEADING_DEG PITCH_DEG"}},
        {"tool", {1, 1, 0, "NAME"}},
        {"set", {2, 2, 0, "KEY VALUE"}},
        {"move", {2, 2, 2, "X Y"}},
        {"press", {0, 1, 0, "[left|right|middle]"}},
        {"release", {0, 1, 0, "[left|right|middle]"}},
        {"click", {0, 1, 0, "[left|right|middle]"}},
        {"drag", {4, 5, -1, "X0 Y0 X1 Y1 [STEPS]"}},
        {"item", {1, 3, 0, "ID [DX DY]"}},
        {"drag-item", {3, 4, 0, "ID DX DY [STEPS]"}},
        {"key", {1, 1, 0, "SPEC (e.g. ctrl+z)"}},
        {"scroll", {1, 1, 1, "STEPS"}},
        {"screenshot", {1, 2, 0, "FILE [ui|3d]"}},
        {"save", {0, 1, 0, "[FILE]"}},
        {"heights", {1, 1, 0, "FILE.f32"}},
        {"undo-all", {0, 0, 0, ""}},
        {"wait-autosave", {0, 0, 0, ""}},
        {"expect-error", {1, 64, 0, "TEXT"}},
        {"expect-ok", {0, 0, 0, ""}},
        {"expect-selected-layer", {1, 1, 1, "INDEX (-1: none)"}},
        {"phase", {1, 1, 0, "NAME"}},
        {"echo", {0, 1, 0, "TEXT"}},
        {"quit", {0, 0, 0, ""}},
    };
    return s;
}

bool parseNumber(const std::string& s, double* out) {
    std::istringstream in(s);
    in >> *out;
    return in && in.peek() == std::char_traits<char>::eof() && std::isfinite(*out);
}

bool isButton(const std::string& s) { return s == "left" || s == "right" || s == "middle"; }

}  // namespace

Result<std::vector<ScriptCommand>> parseScript(const std::string& text, const std::string& path) {
    std::vector<ScriptCommand> out;
    std::istringstream lines(text);
    std::string line;
    int number = 0;
    while (std::getline(lines, line)) {
        ++number;
        if (const size_t hash = line.find('#'); hash != std::string::npos) line.erase(hash);
        std::istringstream words(line);
        ScriptCommand c;
        c.line = number;
        if (!(words >> c.op)) continue;
        auto fail = [&](const std::string& why) {
            return Status::error(path + ":" + std::to_string(number) + ": " + c.op + ": " + why);
        };
        auto it = shapes().find(c.op);
        if (it == shapes().end()) return Status::error(path + ":" + std::to_string(number) + ": unknown command '" + c.op + "'");
        const Shape& shape = it->second;
        if (c.op == "echo" || c.op == "expect-error") {
            std::string rest;
            std::getline(words, rest);
            rest.erase(0, rest.find_first_not_of(" \t"));
            while (!rest.empty() && std::isspace(static_cast<unsigned char>(rest.back()))) rest.pop_back();
            if (c.op == "expect-error" && rest.empty()) return fail(std::string("needs ") + shape.usage);
            if (!rest.empty()) c.args.push_back(rest);
            out.push_back(c);
            continue;
        }
        for (std::string w; words >> w;) c.args.push_back(w);
        if (c.op == "set" && c.args.size() > 2) {
            // Values may hold blanks (type names such as "extreme alpine").
            for (size_t i = 2; i < c.args.size(); ++i) c.args[1] += " " + c.args[i];
            c.args.resize(2);
        }
        const int n = static_cast<int>(c.args.size());
        if (n < shape.min_args || n > shape.max_args) return fail(std::string("needs ") + shape.usage);
        const int numeric = shape.numeric < 0 ? n : std::min(shape.numeric, n);
        for (int i = 0; i < numeric; ++i) {
            double v = 0;
            if (!parseNumber(c.args[static_cast<size_t>(i)], &v)) return fail("'" + c.args[static_cast<size_t>(i)] + "' is not a number");
            c.numbers.push_back(v);
        }
        if (c.op == "view") {
            const std::string& mode = c.args[0];
            if (!((mode == "aerial" && n == 4) || (mode == "free" && n == 6))) return fail(std::string("needs ") + shape.usage);
            for (int i = 1; i < n; ++i) {
                double v = 0;
                if (!parseNumber(c.args[static_cast<size_t>(i)], &v)) return fail("'" + c.args[static_cast<size_t>(i)] + "' is not a number");
                c.numbers.push_back(v);
            }
            if (c.numbers[2] <= 0) return fail("the width or distance must be > 0");
        }
        if ((c.op == "press" || c.op == "release" || c.op == "click") && n == 1 && !isButton(c.args[0]))
            return fail("unknown button '" + c.args[0] + "' (left, right or middle)");
        if (c.op == "item" && n > 1) {
            if (n != 3) return fail(std::string("needs ") + shape.usage);
            for (int i = 1; i < 3; ++i) {
                double v = 0;
                if (!parseNumber(c.args[static_cast<size_t>(i)], &v)) return fail("'" + c.args[static_cast<size_t>(i)] + "' is not a number");
                c.numbers.push_back(v);
            }
        }
        if (c.op == "drag-item") {
            for (int i = 1; i < n; ++i) {
                double v = 0;
                if (!parseNumber(c.args[static_cast<size_t>(i)], &v)) return fail("'" + c.args[static_cast<size_t>(i)] + "' is not a number");
                c.numbers.push_back(v);
            }
            if (n == 4 && (c.numbers[2] < 1 || c.numbers[2] > 10000)) return fail("STEPS must be in 1..10000");
        }
        if (c.op == "key") {
            int key = 0, mods = 0;
            if (!parseKeySpec(c.args[0], &key, &mods)) return fail("unknown key '" + c.args[0] + "'");
        }
        if (c.op == "screenshot" && n == 2 && c.args[1] != "ui" && c.args[1] != "3d")
            return fail("the second argument is ui or 3d, got '" + c.args[1] + "'");
        if ((c.op == "wait" || c.op == "sleep" || c.op == "settle") && !c.numbers.empty() && c.numbers[0] < 0)
            return fail("must not be negative");
        if (c.op == "drag" && n == 5 && (c.numbers[4] < 1 || c.numbers[4] > 10000))
            return fail("STEPS must be in 1..10000");
        out.push_back(c);
    }
    return out;
}

Result<std::vector<ScriptCommand>> readScript(const std::string& path) {
    auto bytes = readFileBytes(path);
    if (!bytes) return bytes.status();
    return parseScript(*bytes, path);
}

bool parseKeySpec(const std::string& spec, int* key, int* mods) {
    std::string s = spec;
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    *mods = 0;
    size_t plus;
    while ((plus = s.find('+')) != std::string::npos && plus + 1 < s.size()) {
        const std::string mod = s.substr(0, plus);
        if (mod == "ctrl") *mods |= GLFW_MOD_CONTROL;
        else if (mod == "shift") *mods |= GLFW_MOD_SHIFT;
        else if (mod == "alt") *mods |= GLFW_MOD_ALT;
        else return false;
        s.erase(0, plus + 1);
    }
    static const std::map<std::string, int> named = {
        {"delete", GLFW_KEY_DELETE}, {"escape", GLFW_KEY_ESCAPE}, {"enter", GLFW_KEY_ENTER},
        {"backspace", GLFW_KEY_BACKSPACE}, {"tab", GLFW_KEY_TAB}, {"space", GLFW_KEY_SPACE},
        {"left", GLFW_KEY_LEFT}, {"right", GLFW_KEY_RIGHT}, {"up", GLFW_KEY_UP}, {"down", GLFW_KEY_DOWN},
    };
    if (auto it = named.find(s); it != named.end()) {
        *key = it->second;
        return true;
    }
    if (s.size() == 1 && s[0] >= 'a' && s[0] <= 'z') {
        *key = GLFW_KEY_A + (s[0] - 'a');
        return true;
    }
    if (s.size() == 1 && s[0] >= '0' && s[0] <= '9') {
        *key = GLFW_KEY_0 + (s[0] - '0');
        return true;
    }
    if (s.size() >= 2 && s[0] == 'f') {
        double f = 0;
        if (parseNumber(s.substr(1), &f) && f >= 1 && f <= 12) {
            *key = GLFW_KEY_F1 + static_cast<int>(f) - 1;
            return true;
        }
    }
    return false;
}

}  // namespace terrasynth::editor
