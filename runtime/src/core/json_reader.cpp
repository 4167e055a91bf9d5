#include "core/json_reader.h"

#include <algorithm>
#include <cmath>

#include "core/number_text.h"
#include "terrasynth/limits.h"

namespace terrasynth::detail {

using nlohmann::json;

namespace {

// Deepest nesting of [ and { outside strings; stops counting once past `limit`.
int nestingDepth(const std::string& text, int limit) {
    int depth = 0, deepest = 0;
    bool in_string = false, escaped = false;
    for (char c : text) {
        if (in_string) {
            if (escaped) escaped = false;
            else if (c == '\\') escaped = true;
            else if (c == '"') in_string = false;
        } else if (c == '"') {
            in_string = true;
        } else if (c == '[' || c == '{') {
            deepest = std::max(deepest, ++depth);
            if (deepest > limit) return deepest;
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
    return deepest;
}

}  // namespace

Result<json> parseJson(const std::string& text, const std::string& where) {
    if (text.size() > limits::kMaxJsonBytes)
        return Status::error(where + ": JSON text of " + std::to_string(text.size()) + " bytes (at most " +
                             std::to_string(limits::kMaxJsonBytes) + ")");
    if (nestingDepth(text, limits::kMaxJsonDepth) > limits::kMaxJsonDepth)
        return Status::error(where + ": JSON nested more than " + std::to_string(limits::kMaxJsonDepth) + " levels deep");
    try {
        return json::parse(text);
    } catch (const json::exception& e) {
        // A syntax error, or a number out of double's range (out_of_range.406); what() is
        // "[json.exception.parse_error.101] parse error at line 1, column 2: ...".
        std::string why = e.what();
        const size_t at = why.find("] ");
        if (at != std::string::npos) why = why.substr(at + 2);
        return Status::error(where + ": malformed JSON: " + why);
    }
}

std::string dumpJson(const json& value, int indent) {
    return value.dump(indent, ' ', /*ensure_ascii=*/false, json::error_handler_t::replace);
}

JsonReader::JsonReader(const json& object, std::string where) : object_(object), where_(std::move(where)) {
    if (!object_.is_object()) fail("", "must be an object");
}

const json* JsonReader::find(const char* key) const {
    if (!object_.is_object()) return nullptr;
    auto it = object_.find(key);
    return it == object_.end() ? nullptr : &*it;
}

bool JsonReader::has(const char* key) const { return find(key) != nullptr; }

std::string JsonReader::field(const std::string& key) const {
    if (where_.empty()) return key;
    return key.empty() ? where_ : where_ + "." + key;
}

void JsonReader::fail(const std::string& key, const std::string& problem) {
    if (error_.empty()) error_ = field(key) + ": " + problem;
}

void JsonReader::failWith(const std::string& message) {
    if (error_.empty()) error_ = message;
}

double JsonReader::number(const char* key, double lo, double hi, std::optional<double> fallback) {
    use(key);
    const json* v = find(key);
    if (!v) {
        if (!fallback) fail(key, "is required");
        return fallback.value_or(0.0);
    }
    if (!v->is_number()) return fail(key, "must be a number"), fallback.value_or(0.0);
    const double d = v->get<double>();
    if (!std::isfinite(d) || d < lo || d > hi) {
        fail(key, "must be in [" + compactNumber(lo) + ", " + compactNumber(hi) + "], got " + compactNumber(d));
        return fallback.value_or(0.0);
    }
    return d;
}

double JsonReader::numberIf(const char* key, double fallback, const std::function<bool(double)>& ok, const char* rule) {
    use(key);
    const json* v = find(key);
    if (!v) return fallback;
    if (!v->is_number()) return fail(key, "must be a number"), fallback;
    const double d = v->get<double>();
    if (!std::isfinite(d) || (ok && !ok(d))) return fail(key, rule), fallback;
    return d;
}

int64_t JsonReader::integer(const char* key, int64_t fallback, int64_t lo, int64_t hi) {
    use(key);
    const json* v = find(key);
    if (!v) return fallback;
    if (!v->is_number()) return fail(key, "must be a number"), fallback;
    // Compare as doubles first: 2^32 + 648 must be refused, not wrapped into range.
    const double d = v->get<double>();
    if (!std::isfinite(d) || d != std::floor(d)) return fail(key, "must be a whole number"), fallback;
    if (d < static_cast<double>(lo) || d > static_cast<double>(hi))
        return fail(key, "must be in " + std::to_string(lo) + ".." + std::to_string(hi) + ", got " + compactNumber(d)),
               fallback;
    return v->is_number_unsigned() ? static_cast<int64_t>(v->get<uint64_t>())
                                   : (v->is_number_integer() ? v->get<int64_t>() : static_cast<int64_t>(d));
}

uint64_t JsonReader::unsignedInteger(const char* key, uint64_t fallback) {
    use(key);
    const json* v = find(key);
    if (!v) return fallback;
    if (v->is_number_unsigned()) return v->get<uint64_t>();
    if (v->is_number_integer() && v->get<int64_t>() >= 0) return static_cast<uint64_t>(v->get<int64_t>());
    return fail(key, "must be a non-negative integer"), fallback;
}

bool JsonReader::boolean(const char* key, bool fallback) {
    use(key);
    const json* v = find(key);
    if (!v) return fallback;
    if (!v->is_boolean()) return fail(key, "must be true or false"), fallback;
    return v->get<bool>();
}

std::string JsonReader::string(const char* key, const std::string& fallback) {
    use(key);
    const json* v = find(key);
    if (!v) return fallback;
    if (!v->is_string()) return fail(key, "must be a string"), fallback;
    return v->get<std::string>();
}

const json* JsonReader::child(const char* key) {
    use(key);
    return find(key);
}

std::vector<double> JsonReader::numbers(const char* key, size_t min_n, size_t max_n) {
    use(key);
    std::vector<double> out;
    const json* v = find(key);
    if (!v) return fail(key, "is required"), out;
    if (!v->is_array() || v->size() < min_n || v->size() > max_n)
        return fail(key, "must be an array of " + std::to_string(min_n) +
                             (min_n == max_n ? "" : ".." + std::to_string(max_n)) + " numbers"),
               out;
    for (const json& e : *v) {
        if (!e.is_number() || !std::isfinite(e.get<double>())) return fail(key, "must contain only numbers"), out;
        out.push_back(e.get<double>());
    }
    return out;
}

void JsonReader::require(const char* key) {
    if (!has(key)) fail(key, "is required");
}

Status JsonReader::finish(bool reject_unknown) {
    if (reject_unknown && error_.empty() && object_.is_object())
        for (auto it = object_.begin(); it != object_.end(); ++it)
            if (!used_.count(it.key())) fail(it.key(), "unknown field");
    return status();
}

}  // namespace terrasynth::detail
