#include "project/edit_sidecar.h"

#include <cstring>

#include <nlohmann/json.hpp>

#include "core/digest.h"
#include "layers/layer_json.h"
#include "terrasynth/layers.h"

namespace terrasynth::project {
namespace {

using nlohmann::json;

template <class T>
void appendRaw(std::string& out, const T& v) {
    out.append(reinterpret_cast<const char*>(&v), sizeof v);
}
template <class T>
void appendBlob(std::string& out, json& list, const char* name, const std::vector<T>& v) {
    list.push_back({{"name", name}, {"bytes", v.size() * sizeof(T)}});
    out.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
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
                         {"digest", detail::digestText(s.digest)},
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
    std::string out(kEditSidecarMagic, sizeof kEditSidecarMagic);
    appendRaw(out, EditSidecar::kVersion);
    appendRaw(out, static_cast<uint64_t>(text.size()));
    out += text;
    out += body;
    appendRaw(out, detail::fnv1a(out.data(), out.size()));
    return out;
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
                                 "," + std::to_string(p.hold_point_heights) +
                                 // Only breach and the relaxation are named, so sidecars saved when both were off keep
                                 // their digests.
                                 (q.drainage == Drainage::Breach ? ",breach" : "") + (q.relax_offsets ? ",relaxed" : "") + "|";
    uint64_t h = detail::fnv1a(settings.data(), settings.size());
    h = detail::fnv1a(constraints.json.data(), constraints.json.size(), h);
    for (const auto& m : constraints.masks) {
        const std::string name = "|" + m.file + "|";
        h = detail::fnv1a(name.data(), name.size(), h);
        h = detail::fnv1a(reinterpret_cast<const char*>(m.pixels.data()), m.pixels.size(), h);
    }
    h = detail::fnv1a("|", 1, h);
    return detail::fnv1a(layers.data(), layers.size(), h);
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
