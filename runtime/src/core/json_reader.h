// Private: the one reader of typed JSON fields (projects, constraints, layers, sidecars).
//
// Reads the fields of one JSON object, remembering only the first problem as
// "<where>.<key>: <problem>" (e.g. "constraints.points[1].radius_px: must be in [0.001, 1e+06], got 0"),
// so a caller reads every field and checks once. finish() also reports fields nobody asked for, so a
// typo never silently becomes a default.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "terrasynth/status.h"

namespace terrasynth::detail {

class JsonReader {
public:
    // `where` names the object in messages ("" = top level: messages start with the key).
    JsonReader(const nlohmann::json& object, std::string where);

    bool has(const char* key) const;
    // A finite number in [lo, hi]; `fallback` when absent (no fallback: "<key>: is required").
    double number(const char* key, double lo, double hi, std::optional<double> fallback);
    // A finite number passing `ok` (else `rule` is the problem); `fallback` when absent.
    double numberIf(const char* key, double fallback, const std::function<bool(double)>& ok = nullptr,
                    const char* rule = "must be a finite number");
    // A whole number in lo..hi (JSON 3.0 counts as whole); `fallback` when absent.
    int64_t integer(const char* key, int64_t fallback, int64_t lo, int64_t hi);
    // A non-negative whole number up to 2^64-1 (seeds); `fallback` when absent.
    uint64_t unsignedInteger(const char* key, uint64_t fallback);
    bool boolean(const char* key, bool fallback);
    std::string string(const char* key, const std::string& fallback);
    // The member (marked as read), null when absent.
    const nlohmann::json* child(const char* key);
    // An array of min_n..max_n finite numbers ("is required" when absent).
    std::vector<double> numbers(const char* key, size_t min_n, size_t max_n);
    void require(const char* key);
    // Marks a key as read without reading it (it is handled elsewhere).
    void use(const char* key) { used_.insert(key); }

    void fail(const std::string& key, const std::string& problem);
    // Records a complete message (e.g. one from a nested reader) if none is recorded yet.
    void failWith(const std::string& message);
    // "<where>.<key>" or "<key>" at the top level.
    std::string field(const std::string& key) const;
    const std::string& where() const { return where_; }
    bool ok() const { return error_.empty(); }
    Status status() const { return ok() ? Status::ok() : Status::error(error_); }
    // The first problem, after reporting unknown fields when `reject_unknown`.
    Status finish(bool reject_unknown = true);

private:
    const nlohmann::json* find(const char* key) const;
    const nlohmann::json& object_;
    std::string where_;
    std::set<std::string> used_;
    std::string error_;
};

// The one JSON parser of the runtime: refuses texts over limits::kMaxJsonBytes or nested deeper
// than limits::kMaxJsonDepth before parsing (so neither the parser nor any later copy of the tree
// can exhaust the stack), then parses. Errors start with `where` (a file or field name):
// "world.tsyn: malformed JSON: syntax error at line 3, column 7: ...".
Result<nlohmann::json> parseJson(const std::string& text, const std::string& where);
// Serialises with invalid UTF-8 (a file name in a legacy encoding) replaced by U+FFFD instead of
// throwing. indent < 0: compact.
std::string dumpJson(const nlohmann::json& value, int indent = -1);

}  // namespace terrasynth::detail
