#include "project/edit_sidecar.h"

#include <cstring>

#include <nlohmann/json.hpp>

#include "layers/layer_json.h"
#include "terrasynth/layers.h"

namespace terrasynth::project {
namespace {

using nlohmann::json;

constexpr char kMagic[8] = {'T', 'S', 'Y', 'N', 'E', 'D', 'I', 'T'};

uint64_t fnv1a(const char* data, size_t n, uint64_t h = 1469598103934665603ull) {
    for (size_t i = 0; i < n; ++i) h = (h ^ static_cast<unsigned char>(data[i])) * 1099511628211ull;
    return h;
}

template <class T>
void appendRaw(std::string& out, const T& v) {
    out.append(reinterpret_cast<const char*>(&v), sizeof v);
}
template <class T>
void appendBlob(std::string& out, json& list, const char* name, const std::vector<T>& v) {
    list.push_back({{"name", name}, {"bytes", v.size() * sizeof(T)}});
    out.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
}

std::string hex(uint64_t v) {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(v));
    return text;
}

// Reads the blobs the header lists, in order, with their declared sizes checked.
class BlobReader {
public:
    BlobReader(const std::string& bytes, size_t offset, size_t end, const std::string& path)
        : bytes_(bytes), offset_(offset), end_(end), path_(path) {}
    template <class T>
    Status read(const json& entry, const char* name, size_t count, std::vector<T>* out) {
        if (!entry.is_object() || entry.value("name", "") != name || !entry.contains("bytes") ||
            !entry["bytes"].is_number_unsigned())
            return Status::error(path_ + ": expected the " + std::string(name) + " section");
        const uint64_t size = entry["bytes"].get<uint64_t>();
        if (size != count * sizeof(T)) return Status::error(path_ + ": " + name + " section has the wrong size");
        if (size > end_ - offset_) return Status::error(path_ + ": truncated in the " + std::string(name) + " section");
        if (out) {
            out->resize(count);
            std::memcpy(out->data(), bytes_.data() + offset_, size);
        }
        offset_ += size;
        return Status::ok();
    }

private:
    const std::string& bytes_;
    size_t offset_, end_;
    std::string path_;
};

Result<json> readHeader(const std::string& bytes, const std::string& path, size_t* blobs_at) {
    const size_t fixed = sizeof kMagic + 4 + 8;
    if (bytes.size() < fixed + 8 || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0)
        return Status::error(path + ": not a terrasynth edited-heights file");
    uint32_t version = 0;
    uint64_t header_bytes = 0;
    std::memcpy(&version, bytes.data() + sizeof kMagic, 4);
    std::memcpy(&header_bytes, bytes.data() + sizeof kMagic + 4, 8);
    if (version != EditSidecar::kVersion)
        return Status::error(path + ": edited-heights version " + std::to_string(version) + " (this build reads " +
                             std::to_string(EditSidecar::kVersion) + ")");
    if (header_bytes > bytes.size() - fixed - 8) return Status::error(path + ": truncated header");
    json header = json::parse(bytes.begin() + fixed, bytes.begin() + fixed + header_bytes, nullptr, false);
    if (header.is_discarded() || !header.is_object()) return Status::error(path + ": malformed header");
    *blobs_at = fixed + header_bytes;
    return header;
}

}  // namespace

ConstraintLifts liftsOf(const SynthesisConstraints* constraints) {
    ConstraintLifts lifts;
    if (!constraints) return lifts;
    for (const PointConstraint& p : constraints->points) {
        lifts.points.push_back(p.lift_m);
        lifts.tilts.push_back({p.tilt_east, p.tilt_south});
        lifts.wide_tilts.push_back({p.wide_tilt_east, p.wide_tilt_south});
    }
    for (const CurveConstraint& c : constraints->curves) lifts.curves.push_back(c.lift_m);
    return lifts;
}

bool applyLifts(const ConstraintLifts& lifts, std::vector<PointConstraint>& points, std::vector<CurveConstraint>& curves) {
    if (lifts.points.size() != points.size() || (!lifts.tilts.empty() && lifts.tilts.size() != points.size()) ||
        (!lifts.wide_tilts.empty() && lifts.wide_tilts.size() != points.size()) ||
        (!lifts.curves.empty() && lifts.curves.size() != curves.size()))
        return false;
    for (size_t i = 0; i < points.size(); ++i) {
        points[i].lift_m = lifts.points[i];
        points[i].tilt_east = lifts.tilts.empty() ? 0.0f : lifts.tilts[i][0];
        points[i].tilt_south = lifts.tilts.empty() ? 0.0f : lifts.tilts[i][1];
        points[i].wide_tilt_east = lifts.wide_tilts.empty() ? 0.0f : lifts.wide_tilts[i][0];
        points[i].wide_tilt_south = lifts.wide_tilts.empty() ? 0.0f : lifts.wide_tilts[i][1];
    }
    for (size_t i = 0; i < curves.size(); ++i) curves[i].lift_m = lifts.curves.empty() ? std::vector<float>() : lifts.curves[i];
    return true;
}

std::string encodeEditSidecar(const EditSidecar& s) {
    json blobs = json::array();
    std::string body;
    appendBlob(body, blobs, "heights", s.heights);
    appendBlob(body, blobs, "frozen", s.frozen);
    json history = json::array();
    for (size_t level = 0; level < s.history.levels.size(); ++level) {
        const auto& l = s.history.levels[level];
        history.push_back({l.x, l.y, l.width, l.height, l.passes.size()});
        for (const auto& pass : l.passes) {
            appendBlob(body, blobs, "history.index", pass.index);
            appendBlob(body, blobs, "history.v", pass.v);
        }
    }
    json reference_masks = json::array();
    for (const auto& m : s.reference.masks) {
        reference_masks.push_back({{"file", m.file}, {"width", m.width}, {"height", m.height}});
        appendBlob(body, blobs, "reference.mask", m.pixels);
    }
    const json header = {{"format", "terrasynth-edited-heights"},
                         {"digest", hex(s.digest)},
                         {"extent", {s.extent.x, s.extent.y, s.extent.width, s.extent.height}},
                         {"lifts", s.lifts.points},
                         {"tilts", s.lifts.tilts},
                         {"wide_tilts", s.lifts.wide_tilts},
                         {"curve_lifts", s.lifts.curves},
                         {"history", history},
                         {"reference", {{"constraints", json::parse(s.reference.json)},
                                        {"masks", reference_masks},
                                        {"lifts", s.reference_lifts.points},
                                        {"tilts", s.reference_lifts.tilts},
                                        {"wide_tilts", s.reference_lifts.wide_tilts},
                                        {"curve_lifts", s.reference_lifts.curves}}},
                         {"blobs", blobs}};
    const std::string text = header.dump();
    std::string out(kMagic, sizeof kMagic);
    appendRaw(out, EditSidecar::kVersion);
    appendRaw(out, static_cast<uint64_t>(text.size()));
    out += text;
    out += body;
    appendRaw(out, fnv1a(out.data(), out.size()));
    return out;
}

Result<uint64_t> sidecarDigest(const std::string& bytes, const std::string& path) {
    size_t blobs_at = 0;
    auto header = readHeader(bytes, path, &blobs_at);
    if (!header) return header.status();
    const json& digest = (*header)["digest"];
    if (!digest.is_string() || digest.get<std::string>().size() != 16) return Status::error(path + ": no digest");
    return std::stoull(digest.get<std::string>(), nullptr, 16);
}

Result<EditSidecar> decodeEditSidecar(const std::string& bytes, const std::string& path, bool with_history) {
    size_t blobs_at = 0;
    auto parsed = readHeader(bytes, path, &blobs_at);
    if (!parsed) return parsed.status();
    uint64_t stored = 0;
    std::memcpy(&stored, bytes.data() + bytes.size() - 8, 8);
    if (stored != fnv1a(bytes.data(), bytes.size() - 8)) return Status::error(path + ": checksum mismatch (corrupt file)");
    const json& h = *parsed;
    EditSidecar s;
    auto digest = sidecarDigest(bytes, path);
    if (!digest) return digest.status();
    s.digest = digest.value();
    const json& extent = h.value("extent", json());
    const json& blobs = h.value("blobs", json());
    const json& history = h.value("history", json());
    const json& reference = h.value("reference", json());
    auto bad = [&](const char* what) { return Status::error(path + ": malformed " + std::string(what)); };
    if (!extent.is_array() || extent.size() != 4 || !blobs.is_array() || !history.is_array() || !reference.is_object())
        return bad("header");
    for (const json& v : extent)
        if (!v.is_number_integer()) return bad("extent");
    const int64_t width = extent[2].get<int64_t>(), height = extent[3].get<int64_t>();
    if (width < 1 || height < 1 || width > 16384 || height > 16384) return bad("extent");
    s.extent = {extent[0].get<int64_t>(), extent[1].get<int64_t>(), static_cast<int>(width), static_cast<int>(height)};
    const size_t pixels = static_cast<size_t>(s.extent.width) * s.extent.height;
    try {
        // Tilts and curve lifts came later: a sidecar without them has none.
        auto readLifts = [](const json& from) {
            ConstraintLifts lifts;
            lifts.points = from.value("lifts", json::array()).get<std::vector<float>>();
            lifts.tilts = from.value("tilts", json::array()).get<std::vector<std::array<float, 2>>>();
            lifts.wide_tilts = from.value("wide_tilts", json::array()).get<std::vector<std::array<float, 2>>>();
            lifts.curves = from.value("curve_lifts", json::array()).get<std::vector<std::vector<float>>>();
            return lifts;
        };
        s.lifts = readLifts(h);
        s.reference_lifts = readLifts(reference);
        s.reference.json = reference.at("constraints").dump();
    } catch (const json::exception&) {
        return bad("lifts or reference");
    }
    BlobReader reader(bytes, blobs_at, bytes.size() - 8, path);
    size_t next = 0;
    auto entry = [&]() -> const json& {
        static const json kNone;
        return next < blobs.size() ? blobs[next++] : kNone;
    };
    if (Status st = reader.read(entry(), "heights", pixels, &s.heights); !st) return st;
    if (Status st = reader.read(entry(), "frozen", pixels, &s.frozen); !st) return st;
    if (with_history) s.history.levels.resize(history.size());
    for (size_t level = 0; level < history.size(); ++level) {
        const json& l = history[level];
        if (!l.is_array() || l.size() != 5) return bad("history");
        for (const json& v : l)
            if (!v.is_number_integer()) return bad("history");
        const int64_t w = l[2].get<int64_t>(), hh = l[3].get<int64_t>(), passes = l[4].get<int64_t>();
        const int64_t limit = int64_t(1) << 29, x = l[0].get<int64_t>(), y = l[1].get<int64_t>();
        if (w < 0 || hh < 0 || w > 65536 || hh > 65536 || passes < 0 || passes > 4 || x < -limit || x > limit ||
            y < -limit || y > limit)
            return bad("history");
        const size_t n = static_cast<size_t>(w) * hh;
        SynthesisHistory::Level* out = with_history ? &s.history.levels[level] : nullptr;
        if (out)
            *out = {static_cast<int>(l[0].get<int64_t>()), static_cast<int>(l[1].get<int64_t>()), static_cast<int>(w),
                    static_cast<int>(hh), std::vector<SynthesisHistory::Pass>(static_cast<size_t>(passes))};
        for (int pass = 0; pass < passes; ++pass) {
            if (Status st = reader.read(entry(), "history.index", n, out ? &out->passes[pass].index : nullptr); !st) return st;
            if (Status st = reader.read(entry(), "history.v", n, out ? &out->passes[pass].v : nullptr); !st) return st;
        }
    }
    const json& masks = reference.value("masks", json::array());
    if (!masks.is_array()) return bad("reference masks");
    for (const json& m : masks) {
        if (!m.is_object() || !m.value("file", json()).is_string() || !m.value("width", json()).is_number_integer() ||
            !m.value("height", json()).is_number_integer())
            return bad("reference masks");
        if (m["width"].get<int64_t>() != s.extent.width || m["height"].get<int64_t>() != s.extent.height)
            return bad("reference masks");
        ConstraintsJson::Mask mask{m["file"].get<std::string>(), s.extent.width, s.extent.height, {}};
        if (Status st = reader.read(entry(), "reference.mask", pixels, &mask.pixels); !st) return st;
        s.reference.masks.push_back(std::move(mask));
    }
    return s;
}

uint64_t editDigest(const Project& p, const ExemplarDatabase& db, const ConstraintsJson& constraints,
                    const std::string& layers) {
    const SynthesisParams& q = p.synthesis;
    uint32_t jitter_bits = 0;
    std::memcpy(&jitter_bits, &q.jitter, 4);
    const std::string settings = "tsyn-edit-1|" + std::to_string(db.input_digest) + "|" + std::to_string(p.origin_x) + "," +
                                 std::to_string(p.origin_y) + "," + std::to_string(p.width) + "," +
                                 std::to_string(p.height) + "|" + std::to_string(q.seed) + "," +
                                 std::to_string(jitter_bits) + "," + std::to_string(q.correction_passes) + "," +
                                 std::to_string(q.coarsest_level) + "," + std::to_string(q.first_constrained_level) +
                                 "," + std::to_string(p.hold_point_heights) + "|";
    uint64_t h = fnv1a(settings.data(), settings.size());
    h = fnv1a(constraints.json.data(), constraints.json.size(), h);
    for (const auto& m : constraints.masks) {
        const std::string name = "|" + m.file + "|";
        h = fnv1a(name.data(), name.size(), h);
        h = fnv1a(reinterpret_cast<const char*>(m.pixels.data()), m.pixels.size(), h);
    }
    h = fnv1a("|", 1, h);
    return fnv1a(layers.data(), layers.size(), h);
}

Result<uint64_t> projectEditDigest(const Project& p, const ExemplarDatabase& db) {
    auto constraints = parseConstraints(p.constraints_json, p.folder(), db, p.origin_x, p.origin_y, p.width, p.height);
    if (!constraints) return constraints.status();
    auto canonical = constraintsToJson(*constraints, db, p.origin_x, p.origin_y, p.width, p.height, "canonical");
    if (!canonical) return canonical.status();
    auto stack = parseLayerStack(p.layers_json, p.folder());
    if (!stack) return stack.status();
    return editDigest(p, db, *canonical, layerStackToJson(*stack));
}

}  // namespace terrasynth::project
