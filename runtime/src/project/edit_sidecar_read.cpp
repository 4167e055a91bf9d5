// Reading an edited-heights sidecar (edit_sidecar.h). The file is one users keep, copy and version,
// so it is validated like a project or a database before anything of it is used: the header is
// parsed with the runtime's bounded JSON parser and read field by field (JsonReader: "file: field:
// problem"), every blob's size is checked against what the header declares, heights and history
// offsets are finite and within limits::kMaxAbsHeightM, the frozen mask holds 0 or 1. What needs
// the database (history atlas indices) is checked by IncrementalTerrain::restore.
#include <cmath>
#include <cstring>

#include "core/digest.h"
#include "core/json_reader.h"
#include "core/number_text.h"
#include "project/edit_sidecar.h"
#include "synth/synthesis_driver.h"
#include "terrasynth/limits.h"

namespace terrasynth::project {
namespace {

using nlohmann::json;
using detail::JsonReader;

constexpr size_t kFixedBytes = sizeof kEditSidecarMagic + 4 + 8;  // magic, version, header length
constexpr const char* kFormat = "terrasynth-edited-heights";
// A curve's lift profile has at most one station per pixel of course (synth/lift_curves.cpp).
constexpr size_t kMaxCurveLiftStations = static_cast<size_t>(limits::kMaxTotalCourseLengthPx) + 2;
constexpr double kMaxTilt = 100.0;  // metres per metre: far beyond any slope a point can ask for

// The header object; `blobs_at` is where the blobs start. Bounded in size and depth (parseJson).
Result<json> readHeader(const std::string& bytes, const std::string& path, size_t* blobs_at) {
    if (bytes.size() < kFixedBytes + 8 || std::memcmp(bytes.data(), kEditSidecarMagic, sizeof kEditSidecarMagic) != 0)
        return Status::error(path + ": not a terrasynth edited-heights file");
    uint32_t version = 0;
    uint64_t header_bytes = 0;
    std::memcpy(&version, bytes.data() + sizeof kEditSidecarMagic, 4);
    std::memcpy(&header_bytes, bytes.data() + sizeof kEditSidecarMagic + 4, 8);
    if (version != EditSidecar::kVersion)
        return Status::error(path + ": edited-heights version " + std::to_string(version) + " (this build reads " +
                             std::to_string(EditSidecar::kVersion) + ")");
    if (header_bytes > bytes.size() - kFixedBytes - 8) return Status::error(path + ": truncated header");
    auto header = detail::parseJson(bytes.substr(kFixedBytes, header_bytes), path + ": header");
    if (!header) return header.status();
    if (!header->is_object()) return Status::error(path + ": header: must be a JSON object");
    *blobs_at = kFixedBytes + header_bytes;
    return header;
}

uint64_t readDigest(JsonReader& r) {
    uint64_t digest = 0;
    const std::string text = r.string("digest", "");
    if (r.ok() && !detail::parseDigestText(text, &digest)) r.fail("digest", "must be 16 hexadecimal digits");
    return digest;
}

// An array of at most `max_n` numbers within +-`bound`, else the problem in `*problem`.
std::vector<float> boundedNumbers(const json& v, size_t max_n, double bound, std::string* problem) {
    std::vector<float> out;
    const auto refuse = [&] {
        *problem = "must be an array of at most " + std::to_string(max_n) + " numbers within +-" + detail::compactNumber(bound);
        return std::vector<float>();
    };
    if (!v.is_array() || v.size() > max_n) return refuse();
    for (const json& e : v) {
        if (!e.is_number() || !(std::fabs(e.get<double>()) <= bound)) return refuse();
        out.push_back(e.get<float>());
    }
    return out;
}

// Point lifts, tilts and curve lift profiles of one constraint set. Tilts, wide tilts and curve
// lifts came later: a sidecar without them has none.
ConstraintLifts readLifts(JsonReader& r) {
    ConstraintLifts lifts;
    const auto max_points = static_cast<size_t>(limits::kMaxPointConstraints);
    std::string problem;
    if (const json* v = r.child("lifts")) {
        lifts.points = boundedNumbers(*v, max_points, limits::kMaxAbsHeightM, &problem);
        if (!problem.empty()) return r.fail("lifts", problem), lifts;
    }
    // Tilts of the site and, beyond it, of half the radius (wide tilts, which came later still).
    for (const char* key : {"tilts", "wide_tilts"}) {
        const json* v = r.child(key);
        if (!v) continue;
        std::vector<std::array<float, 2>>& into = std::string(key) == "tilts" ? lifts.tilts : lifts.wide_tilts;
        if (!v->is_array() || v->size() > max_points)
            return r.fail(key, "must be an array of at most " + std::to_string(max_points) + " pairs"), lifts;
        for (size_t i = 0; i < v->size(); ++i) {
            const std::vector<float> pair = boundedNumbers((*v)[i], 2, kMaxTilt, &problem);
            if (!problem.empty() || pair.size() != 2)
                return r.fail(std::string(key) + "[" + std::to_string(i) + "]",
                              "must be [east, south], each within +-" + detail::compactNumber(kMaxTilt)), lifts;
            into.push_back({pair[0], pair[1]});
        }
    }
    if (const json* v = r.child("curve_lifts")) {
        const auto max_curves = static_cast<size_t>(limits::kMaxCurves);
        if (!v->is_array() || v->size() > max_curves)
            return r.fail("curve_lifts", "must be an array of at most " + std::to_string(max_curves) + " lift profiles"), lifts;
        for (size_t i = 0; i < v->size(); ++i) {
            lifts.curves.push_back(boundedNumbers((*v)[i], kMaxCurveLiftStations, limits::kMaxAbsHeightM, &problem));
            if (!problem.empty()) return r.fail("curve_lifts[" + std::to_string(i) + "]", problem), lifts;
        }
    }
    return lifts;
}

PixelWindow readExtent(JsonReader& r) {
    PixelWindow e;
    const json* v = r.child("extent");
    if (!v) return r.fail("extent", "is required"), e;
    const int64_t origin = limits::kMaxProjectOrigin, side = limits::kMaxWindowSide;
    const std::string rule = "must be [x, y, width, height]: x and y whole numbers within +-" + std::to_string(origin) +
                             ", width and height 1.." + std::to_string(side);
    if (!v->is_array() || v->size() != 4) return r.fail("extent", rule), e;
    for (const json& n : *v)
        if (!n.is_number_integer()) return r.fail("extent", rule), e;
    const auto at = [&](int k) { return (*v)[k].is_number_unsigned() && (*v)[k].get<uint64_t>() > uint64_t(INT64_MAX) ? INT64_MAX : (*v)[k].get<int64_t>(); };
    const int64_t x = at(0), y = at(1), w = at(2), h = at(3);
    if (x < -origin || x > origin || y < -origin || y > origin || w < 1 || w > side || h < 1 || h > side)
        return r.fail("extent", rule), e;
    return {x, y, static_cast<int>(w), static_cast<int>(h)};
}

// Reads the blobs the header lists, in order, with their declared sizes checked.
class BlobReader {
public:
    BlobReader(const std::string& bytes, size_t offset, size_t end, const json& list)
        : bytes_(bytes), offset_(offset), end_(end), list_(list) {}
    // The next blob, which must be `name` of `count` elements; out null: skipped.
    template <class T>
    Status read(const std::string& name, size_t count, std::vector<T>* out) {
        const std::string field = "blobs[" + std::to_string(next_) + "]";
        if (next_ >= list_.size()) return Status::error("blobs: the " + name + " section is missing");
        const json& entry = list_[next_++];
        if (!entry.is_object() || entry.size() != 2 || !entry.contains("name") || entry["name"] != name ||
            !entry.contains("bytes") || !entry["bytes"].is_number_unsigned())
            return Status::error(field + ": expected {\"name\": \"" + name + "\", \"bytes\": N}");
        const uint64_t size = entry["bytes"].get<uint64_t>();
        if (size != count * sizeof(T))
            return Status::error(field + ": " + name + " has " + std::to_string(size) + " bytes, the header implies " +
                                 std::to_string(count * sizeof(T)));
        if (size > end_ - offset_) return Status::error(field + ": truncated in the " + name + " section");
        if (out) {
            out->resize(count);
            if (size) std::memcpy(out->data(), bytes_.data() + offset_, size);
        }
        offset_ += size;
        return Status::ok();
    }
    // Every listed blob read and the file ends right after them.
    Status finish() const {
        if (next_ != list_.size()) return Status::error("blobs: " + std::to_string(list_.size() - next_) + " sections nobody reads");
        if (offset_ != end_) return Status::error("blobs: " + std::to_string(end_ - offset_) + " bytes after the last section");
        return Status::ok();
    }

private:
    const std::string& bytes_;
    size_t offset_, end_;
    const json& list_;
    size_t next_ = 0;
};

// Every value finite and within +-limits::kMaxAbsHeightM; the error names the first that is not.
Status checkHeights(const std::vector<float>& values, const std::string& field) {
    for (size_t i = 0; i < values.size(); ++i)
        if (!(std::fabs(values[i]) <= limits::kMaxAbsHeightM))
            return Status::error(field + ": value " + std::to_string(i) + " is " + detail::compactNumber(values[i]) +
                                 " (heights are finite and within +-" + detail::compactNumber(limits::kMaxAbsHeightM) + " m)");
    return Status::ok();
}

// One history level: [x, y, width, height, passes] within the synthesis grid.
Status readHistoryLevel(const json& l, const std::string& field, SynthesisHistory::Level* out) {
    const int64_t origin = limits::kMaxWindowOrigin;
    const std::string rule = "must be [x, y, width, height, passes]: x and y within +-" + std::to_string(origin) +
                             ", width and height 0..65536, passes 0.." +
                             std::to_string(synth::kMaxHistoryPassesPerLevel);
    if (!l.is_array() || l.size() != 5) return Status::error(field + ": " + rule);
    for (const json& v : l)
        if (!v.is_number_integer() || (v.is_number_unsigned() && v.get<uint64_t>() > uint64_t(INT64_MAX)))
            return Status::error(field + ": " + rule);
    const int64_t x = l[0].get<int64_t>(), y = l[1].get<int64_t>(), w = l[2].get<int64_t>(), h = l[3].get<int64_t>(),
                  passes = l[4].get<int64_t>();
    if (w < 0 || h < 0 || w > 65536 || h > 65536 || passes < 0 || passes > synth::kMaxHistoryPassesPerLevel || x < -origin || x > origin ||
        y < -origin || y > origin)
        return Status::error(field + ": " + rule);
    *out = {static_cast<int>(x), static_cast<int>(y), static_cast<int>(w), static_cast<int>(h),
            std::vector<SynthesisHistory::Pass>(static_cast<size_t>(passes))};
    return Status::ok();
}

Status readBody(const std::string& bytes, size_t blobs_at, const json& header, bool with_history, EditSidecar& s) {
    JsonReader r(header, "");
    if (r.string("format", kFormat) != kFormat) r.fail("format", std::string("must be \"") + kFormat + "\"");
    s.digest = readDigest(r);
    s.extent = readExtent(r);
    s.lifts = readLifts(r);
    const json* history = r.child("history");
    if (r.ok() && history && !history->is_array()) r.fail("history", "must be an array of levels");
    const json* blobs = r.child("blobs");
    if (r.ok() && (!blobs || !blobs->is_array())) r.fail("blobs", "must be an array of sections");
    const json* reference = r.child("reference");
    if (r.ok() && (!reference || !reference->is_object())) r.fail("reference", "must be an object");
    if (Status st = r.finish(); !st) return st;

    JsonReader ref(*reference, "reference");
    const json* constraints = ref.child("constraints");
    if (!constraints || !constraints->is_object()) ref.fail("constraints", "must be an object");
    else s.reference.json = detail::dumpJson(*constraints);
    s.reference_lifts = readLifts(ref);
    const json* masks = ref.child("masks");
    if (ref.ok() && masks && !masks->is_array()) ref.fail("masks", "must be an array");
    if (Status st = ref.finish(); !st) return st;

    BlobReader blob(bytes, blobs_at, bytes.size() - 8, *blobs);
    const size_t pixels = static_cast<size_t>(s.extent.width) * s.extent.height;
    if (Status st = blob.read("heights", pixels, &s.heights); !st) return st;
    if (Status st = checkHeights(s.heights, "heights"); !st) return st;
    if (Status st = blob.read("frozen", pixels, &s.frozen); !st) return st;
    for (size_t i = 0; i < s.frozen.size(); ++i)
        if (s.frozen[i] > 1) return Status::error("frozen: pixel " + std::to_string(i) + " is " + std::to_string(s.frozen[i]) + " (0 or 1)");
    const size_t levels = history ? history->size() : 0;
    if (with_history) s.history.levels.resize(levels);
    for (size_t level = 0; level < levels; ++level) {
        const std::string field = "history[" + std::to_string(level) + "]";
        SynthesisHistory::Level read;
        if (Status st = readHistoryLevel((*history)[level], field, &read); !st) return st;
        const size_t n = static_cast<size_t>(read.width) * read.height;
        for (size_t pass = 0; pass < read.passes.size(); ++pass) {
            SynthesisHistory::Pass* out = with_history ? &read.passes[pass] : nullptr;
            if (Status st = blob.read("history.index", n, out ? &out->index : nullptr); !st) return st;
            if (Status st = blob.read("history.v", n, out ? &out->v : nullptr); !st) return st;
            if (out)
                if (Status st = checkHeights(out->v, field + ".pass[" + std::to_string(pass) + "].v"); !st) return st;
        }
        if (with_history) s.history.levels[level] = std::move(read);
    }
    for (size_t k = 0; masks && k < masks->size(); ++k) {
        const std::string field = "reference.masks[" + std::to_string(k) + "]";
        JsonReader m((*masks)[k], field);
        ConstraintsJson::Mask mask;
        mask.file = m.string("file", "");
        mask.width = static_cast<int>(m.integer("width", 0, s.extent.width, s.extent.width));
        mask.height = static_cast<int>(m.integer("height", 0, s.extent.height, s.extent.height));
        m.require("file"), m.require("width"), m.require("height");
        if (Status st = m.finish(); !st) return st;
        if (Status st = blob.read("reference.mask", pixels, &mask.pixels); !st) return st;
        s.reference.masks.push_back(std::move(mask));
    }
    return blob.finish();
}

}  // namespace

Result<uint64_t> sidecarDigest(const std::string& bytes, const std::string& path) {
    size_t blobs_at = 0;
    auto header = readHeader(bytes, path, &blobs_at);
    if (!header) return header.status();
    JsonReader r(*header, "");
    const uint64_t digest = readDigest(r);
    if (!r.has("digest")) r.fail("digest", "is required");
    if (Status s = r.status(); !s) return s.withContext(path);
    return digest;
}

Result<EditSidecar> decodeEditSidecar(const std::string& bytes, const std::string& path, bool with_history) {
    size_t blobs_at = 0;
    auto header = readHeader(bytes, path, &blobs_at);
    if (!header) return header.status();
    uint64_t stored = 0;
    std::memcpy(&stored, bytes.data() + bytes.size() - 8, 8);
    if (stored != detail::fnv1a(bytes.data(), bytes.size() - 8)) return Status::error(path + ": checksum mismatch (corrupt file)");
    EditSidecar s;
    if (Status st = readBody(bytes, blobs_at, *header, with_history, s); !st) return st.withContext(path);
    return s;
}

}  // namespace terrasynth::project
