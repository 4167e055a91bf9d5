#include "layers/layer_json.h"

#include "core/json_reader.h"
#include "core/paths.h"
#include "terrasynth/heightfield_io.h"
#include "terrasynth/limits.h"

#include <cmath>
#include <functional>
#include <set>

namespace terrasynth::layers {
namespace {

using nlohmann::json;

using Reader = detail::JsonReader;

Point2 readPoint(Reader& r, const json& v, const std::string& field) {
    if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number())
        return r.fail(field, "must be a point [x, y]"), Point2{};
    return {v[0].get<double>(), v[1].get<double>()};
}

Line2 readLine(Reader& r, const json* v, const std::string& field) {
    if (!v || !v->is_array() || v->size() != 2) return r.fail(field, "must be a line [[x, y], [x, y]]"), Line2{};
    return {readPoint(r, (*v)[0], field), readPoint(r, (*v)[1], field)};
}

auto positive = [](double v) { return v > 0; };

BandWeights readWeights(Reader& r, BandWeights def) {
    const json* w = r.child("weights");
    if (!w) return def;
    Reader wr(*w, r.where() + ".weights");
    auto in = [](double v) { return v >= 0 && v <= kMaxBandWeight; };
    const char* rule = "must be in [0, 4]";
    BandWeights out;
    out.low = static_cast<float>(wr.numberIf("low", def.low, in, rule));
    out.mid = static_cast<float>(wr.numberIf("mid", def.mid, in, rule));
    out.high = static_cast<float>(wr.numberIf("high", def.high, in, rule));
    if (Status s = wr.finish(); !s) r.failWith(s.message());
    return out;
}

Region readRegion(Reader& r, const char* key) {
    Region reg;
    const json* v = r.child(key);
    if (!v) return r.fail(key, "is required"), reg;
    Reader rr(*v, r.where() + "." + key);
    const std::string shape = rr.string("shape", "ellipse");
    if (shape == "rect") reg.shape = RegionShape::Rect;
    else if (shape != "ellipse") rr.fail("shape", "must be \"ellipse\" or \"rect\"");
    const std::vector<double> rect = rr.numbers("rect", 4, 4);
    if (rect.size() == 4) {
        reg = Region{reg.shape, rect[0], rect[1], rect[2], rect[3]};
        if (!(rect[2] >= 1 && rect[3] >= 1)) rr.fail("rect", "width and height must be >= 1");
    }
    if (Status s = rr.finish(); !s) r.failWith(s.message());
    return reg;
}

void readFractalFields(Reader& r, FractalParams& f) {
    f.seed = r.unsignedInteger("seed", f.seed);
    f.amplitude_m = r.numberIf("amplitude_m", f.amplitude_m);
    f.offset_m = r.numberIf("offset_m", f.offset_m);
    f.wavelength_px = r.numberIf("wavelength_px", f.wavelength_px);
    f.octaves = r.integer("octaves", f.octaves, 1, 16);
    f.gain = r.numberIf("gain", f.gain);
    f.lacunarity = r.numberIf("lacunarity", f.lacunarity);
    f.roughness = r.numberIf("roughness", f.roughness);
    if (Status s = validateFractal(f); !s) {
        const std::string m = s.message();
        r.fail(m.substr(0, m.find(':')), m.substr(m.find(':') + 2));
    }
}

json regionToJson(const Region& r) {
    return {{"shape", r.shape == RegionShape::Rect ? "rect" : "ellipse"}, {"rect", {r.x, r.y, r.width, r.height}}};
}
json lineToJson(const Line2& l) { return {{l.a.x, l.a.y}, {l.b.x, l.b.y}}; }

void fractalToJson(const FractalParams& f, json& j) {
    j["seed"] = f.seed;
    j["amplitude_m"] = f.amplitude_m;
    j["offset_m"] = f.offset_m;
    j["wavelength_px"] = f.wavelength_px;
    if (f.kind == FractalKind::Fbm) {
        j["octaves"] = f.octaves;
        j["gain"] = f.gain;
        j["lacunarity"] = f.lacunarity;
    } else {
        j["roughness"] = f.roughness;
    }
}

// Moves a tool validator's "field: problem" message onto the reader.
void adopt(Reader& r, const Status& s) {
    if (s) return;
    const std::string& m = s.message();
    const size_t colon = m.find(": ");
    if (colon == std::string::npos) r.fail("", m);
    else r.fail(m.substr(0, colon), m.substr(colon + 2));
}

ToolParams readPeak(Reader& r) {
    PeakParams p;
    const std::vector<double> c = r.numbers("center", 2, 2);
    if (c.size() == 2) p.center_x = c[0], p.center_y = c[1];
    r.require("height_m");
    p.height_m = r.numberIf("height_m", p.height_m);
    p.spread_px = r.numberIf("spread_px", p.spread_px, positive, "must be > 0");
    p.skewness = r.numberIf("skewness", p.skewness);
    p.kurtosis = r.numberIf("kurtosis", p.kurtosis);
    p.skew_azimuth_deg = r.numberIf("skew_azimuth_deg", p.skew_azimuth_deg);
    auto solved = solvePeakShape(p);
    if (!solved) adopt(r, solved.status());
    return p;
}

ToolParams readRidge(Reader& r) {
    RidgeParams p;
    const json* pts = r.child("points");
    if (!pts || !pts->is_array()) {
        r.fail("points", "must be an array of [x, y] points");
    } else {
        for (size_t i = 0; i < pts->size(); ++i) {
            const Point2 q = readPoint(r, (*pts)[i], "points[" + std::to_string(i) + "]");
            p.points.push_back({q.x, q.y});
        }
    }
    const json* prof = r.child("profile_m");
    if (prof && prof->is_number()) p.profile_m = {prof->get<double>()};
    else if (prof && prof->is_array()) p.profile_m = r.numbers("profile_m", 1, 100000);
    else r.fail("profile_m", "must be a height or an array of heights");
    p.width_px = r.numberIf("width_px", p.width_px, positive, "must be > 0");
    adopt(r, validateRidge(p));
    return p;
}

ToolParams readPaste(Reader& r) {
    PasteParams p;
    p.source = r.string("source", p.source);
    if (p.source.empty()) r.fail("source", "must be \"terrain\" or a DEM path");
    const std::vector<double> s = r.numbers("source_xy", 2, 2);
    if (s.size() == 2) p.source_x = s[0], p.source_y = s[1];
    p.dest = readRegion(r, "dest");
    const std::string blend = r.string("blend", "max_gradient");
    if (blend == "replace") p.blend = PasteBlend::Replace;
    else if (blend != "max_gradient") r.fail("blend", "must be \"max_gradient\" or \"replace\"");
    p.match_height = r.boolean("match_height", p.match_height);
    p.vertical_scale = r.numberIf("vertical_scale", p.vertical_scale, [](double v) { return v > 0 && v <= 10; }, "must be in (0, 10]");
    p.feather_px = r.numberIf("feather_px", p.feather_px, [](double v) { return v >= 0 && v <= 1e4; }, "must be >= 0");
    return p;
}

ToolParams readHoleFill(Reader& r) {
    HoleFillParams p;
    p.hole = readRegion(r, "hole");
    p.patch_px = r.integer("patch_px", p.patch_px, 8, 128);
    p.overlap_px = r.integer("overlap_px", p.overlap_px, 2, 64);
    if (p.overlap_px > p.patch_px / 2) r.fail("overlap_px", "must be at most patch_px/2");
    p.seed = r.unsignedInteger("seed", p.seed);
    p.candidates = r.integer("candidates", p.candidates, 16, 20000);
    p.guide_weight = r.numberIf("guide_weight", p.guide_weight, [](double v) { return v >= 0 && v < 1; }, "must be in [0, 1)");
    if (const json* c = r.child("choices")) {
        p.choices.clear();
        if (!c->is_array() || c->empty()) r.fail("choices", "must be a non-empty array of picks 0..2");
        else if (c->size() > static_cast<size_t>(limits::kMaxHoleFillPicks))
            r.fail("choices", std::to_string(c->size()) + " picks, at most " + std::to_string(limits::kMaxHoleFillPicks) +
                                  " (each is a generation of three quilts)");
        else
            for (const json& e : *c) {
                // Read as 64 bits: 2^32 + 1 must not wrap into a valid pick.
                if (!e.is_number_integer() || e.get<int64_t>() < 0 || e.get<int64_t>() > 2) {
                    r.fail("choices", "each pick must be 0, 1 or 2");
                    break;
                }
                p.choices.push_back(static_cast<int>(e.get<int64_t>()));
            }
    }
    return p;
}

ToolParams readPerspective(Reader& r) {
    PerspectiveParams p;
    p.reference_image = r.string("reference_image", "");
    PerspectiveCanvas& c = p.canvas;
    const std::vector<double> size = r.numbers("image_size", 2, 2);
    if (size.size() == 2) {
        // Checked as doubles before narrowing (1e57 as an int is undefined; found by fuzzing).
        auto side = [](double v) { return v >= 1.0 && v <= limits::kMaxImageSide && v == std::floor(v); };
        if (side(size[0]) && side(size[1]))
            c.image_width = static_cast<int>(size[0]), c.image_height = static_cast<int>(size[1]);
        else
            r.fail("image_size", "must be two whole numbers 1.." + std::to_string(limits::kMaxImageSide));
    }
    c.horizon = readLine(r, r.child("horizon"), "horizon");
    if (const json* g = r.child("grid")) {
        Reader gr(*g, r.where() + ".grid");
        c.grid_left = readLine(gr, gr.child("left"), "left");
        c.grid_right = readLine(gr, gr.child("right"), "right");
        c.grid_near = readLine(gr, gr.child("near"), "near");
        c.grid_far = readLine(gr, gr.child("far"), "far");
        if (Status s = gr.finish(); !s) r.failWith(s.message());
    } else {
        r.fail("grid", "is required (left, right, near and far lines)");
    }
    const json* ground = r.child("ground");
    if (!ground || !ground->is_array() || ground->size() != 4) {
        r.fail("ground", "must be 4 terrain points [near-left, near-right, far-right, far-left]");
    } else {
        for (int i = 0; i < 4; ++i) c.ground[i] = readPoint(r, (*ground)[i], "ground[" + std::to_string(i) + "]");
    }
    c.camera_height_m = r.numberIf("camera_height_m", c.camera_height_m, positive, "must be > 0");
    const json* strokes = r.child("strokes");
    if (!strokes || !strokes->is_array()) {
        r.fail("strokes", "must be an array of strokes");
        return p;
    }
    for (size_t i = 0; i < strokes->size(); ++i) {
        const std::string sw = "strokes[" + std::to_string(i) + "]";
        Reader sr((*strokes)[i], r.where() + "." + sw);
        SilhouetteStroke st;
        const json* pts = sr.child("points");
        if (!pts || !pts->is_array()) sr.fail("points", "must be an array of [u, v] image points");
        else
            for (size_t k = 0; k < pts->size(); ++k) st.points.push_back(readPoint(sr, (*pts)[k], "points"));
        if (sr.has("base_v")) st.base_v = sr.numberIf("base_v", 0.0);
        st.width_px = sr.numberIf("width_px", st.width_px, positive, "must be > 0");
        if (Status s = sr.finish(); !s) r.failWith(s.message());
        p.strokes.push_back(std::move(st));
    }
    auto ridges = strokesToRidges(c, p.strokes);
    if (!ridges) adopt(r, ridges.status());
    return p;
}

ToolParams readNoise(Reader& r) {
    NoiseParams p;
    p.fractal.amplitude_m = 50.0;
    p.fractal.wavelength_px = 64.0;
    const std::string kind = r.string("noise", "fbm");
    if (kind == "diamond_square") p.fractal.kind = FractalKind::DiamondSquare;
    else if (kind != "fbm") r.fail("noise", "must be \"fbm\" or \"diamond_square\"");
    readFractalFields(r, p.fractal);
    if (r.has("region")) p.region = readRegion(r, "region");
    p.feather_px = r.numberIf("feather_px", p.feather_px, [](double v) { return v >= 0 && v <= 1e4; }, "must be >= 0");
    return p;
}

}  // namespace

uint64_t fingerprint(const std::string& bytes, uint64_t seed) {
    uint64_t h = seed;
    for (unsigned char c : bytes) h = (h ^ c) * 1099511628211ull;
    return h;
}

Result<EditLayer> parseEditLayer(const json& j, const std::string& where) {
    Reader r(j, where);
    if (!j.is_object()) return r.finish();
    EditLayer layer;
    const std::string type = r.string("type", "");
    layer.name = r.string("name", type);
    layer.visible = r.boolean("visible", true);
    if (type == "peak") layer.tool = readPeak(r);
    else if (type == "ridge") layer.tool = readRidge(r);
    else if (type == "paste") layer.tool = readPaste(r);
    else if (type == "hole_fill") layer.tool = readHoleFill(r);
    else if (type == "perspective") layer.tool = readPerspective(r);
    else if (type == "noise") layer.tool = readNoise(r);
    else if (type == "group") {
        GroupParams g;
        const json* kids = r.child("layers");
        if (!kids || !kids->is_array() || kids->empty()) {
            r.fail("layers", "must be a non-empty array of layers");
        } else {
            for (size_t i = 0; i < kids->size(); ++i) {
                auto child = parseEditLayer((*kids)[i], where + ".layers[" + std::to_string(i) + "]");
                if (!child) return child.status();
                g.children.push_back(std::move(*child));
            }
        }
        layer.tool = std::move(g);
    } else if (type == "base") {
        r.fail("type", "the base layer must be the first element");
    } else {
        r.fail("type", type.empty() ? "is required" : "unknown layer type \"" + type + "\"");
    }
    layer.weights = readWeights(r, defaultWeights(layer.tool));
    if (Status s = r.finish(); !s) return s;
    return layer;
}

json toolToJson(const ToolParams& tool) {
    json j;
    j["type"] = toolTypeName(tool);
    if (auto* p = std::get_if<PeakParams>(&tool)) {
        j["center"] = {p->center_x, p->center_y};
        j["height_m"] = p->height_m;
        j["spread_px"] = p->spread_px;
        j["skewness"] = p->skewness;
        j["kurtosis"] = p->kurtosis;
        j["skew_azimuth_deg"] = p->skew_azimuth_deg;
    } else if (auto* p = std::get_if<RidgeParams>(&tool)) {
        j["points"] = json::array();
        for (auto& q : p->points) j["points"].push_back({q[0], q[1]});
        j["profile_m"] = p->profile_m;
        j["width_px"] = p->width_px;
    } else if (auto* p = std::get_if<PasteParams>(&tool)) {
        j["source"] = p->source;
        j["source_xy"] = {p->source_x, p->source_y};
        j["dest"] = regionToJson(p->dest);
        j["blend"] = p->blend == PasteBlend::Replace ? "replace" : "max_gradient";
        j["match_height"] = p->match_height;
        j["vertical_scale"] = p->vertical_scale;
        j["feather_px"] = p->feather_px;
    } else if (auto* p = std::get_if<HoleFillParams>(&tool)) {
        j["hole"] = regionToJson(p->hole);
        j["patch_px"] = p->patch_px;
        j["overlap_px"] = p->overlap_px;
        j["seed"] = p->seed;
        j["candidates"] = p->candidates;
        j["choices"] = p->choices;
        j["guide_weight"] = p->guide_weight;
    } else if (auto* p = std::get_if<PerspectiveParams>(&tool)) {
        const PerspectiveCanvas& c = p->canvas;
        if (!p->reference_image.empty()) j["reference_image"] = p->reference_image;
        j["image_size"] = {c.image_width, c.image_height};
        j["horizon"] = lineToJson(c.horizon);
        j["grid"] = {{"left", lineToJson(c.grid_left)}, {"right", lineToJson(c.grid_right)},
                     {"near", lineToJson(c.grid_near)}, {"far", lineToJson(c.grid_far)}};
        j["ground"] = json::array();
        for (const Point2& g : c.ground) j["ground"].push_back({g.x, g.y});
        j["camera_height_m"] = c.camera_height_m;
        j["strokes"] = json::array();
        for (const SilhouetteStroke& s : p->strokes) {
            json sj;
            sj["points"] = json::array();
            for (const Point2& q : s.points) sj["points"].push_back({q.x, q.y});
            if (s.base_v) sj["base_v"] = *s.base_v;
            sj["width_px"] = s.width_px;
            j["strokes"].push_back(std::move(sj));
        }
    } else if (auto* p = std::get_if<NoiseParams>(&tool)) {
        j["noise"] = p->fractal.kind == FractalKind::Fbm ? "fbm" : "diamond_square";
        fractalToJson(p->fractal, j);
        if (p->region) j["region"] = regionToJson(*p->region);
        j["feather_px"] = p->feather_px;
    } else if (auto* p = std::get_if<GroupParams>(&tool)) {
        j["layers"] = json::array();
        for (const EditLayer& c : p->children) j["layers"].push_back(editLayerToJson(c));
    }
    return j;
}

json editLayerToJson(const EditLayer& layer) {
    json j = toolToJson(layer.tool);
    j["name"] = layer.name;
    j["visible"] = layer.visible;
    j["weights"] = {{"low", layer.weights.low}, {"mid", layer.weights.mid}, {"high", layer.weights.high}};
    return j;
}

json baseToJson(const BaseLayer& b, const BandSplit& split) {
    json j;
    j["type"] = "base";
    switch (b.source) {
        case BaseSource::Synthesized: j["source"] = "synthesized"; break;
        case BaseSource::Heightmap: j["source"] = "heightmap"; j["path"] = b.path; break;
        case BaseSource::Blank: j["source"] = "blank"; j["height_m"] = b.height_m; break;
        case BaseSource::Fractal:
            j["source"] = b.fractal.kind == FractalKind::Fbm ? "fbm" : "diamond_square";
            fractalToJson(b.fractal, j);
            break;
    }
    j["band_cuts_px"] = {split.high_mid_cut_px, split.mid_low_cut_px};
    j["weights"] = {{"low", b.weights.low}, {"mid", b.weights.mid}, {"high", b.weights.high}};
    return j;
}

}  // namespace terrasynth::layers

namespace terrasynth {

using nlohmann::json;

Result<LayerStack> layers::parseLayerStackJson(const json& layers, const std::string& base_dir) {
    LayerStack stack;
    stack.base_dir = base_dir;
    if (layers.is_null()) return stack;
    if (!layers.is_array()) return Status::error("layers: must be an array");
    size_t first = 0;
    // Compared as JSON: value("type", "") would throw on a non-string type.
    if (!layers.empty() && layers[0].is_object() && layers[0].contains("type") && layers[0]["type"] == "base") {
        first = 1;
        layers::Reader r(layers[0], "layers[0]");
        r.use("type");
        const std::string src = r.string("source", "synthesized");
        BaseLayer& b = stack.base;
        if (src == "synthesized") b.source = BaseSource::Synthesized;
        else if (src == "heightmap") {
            b.source = BaseSource::Heightmap;
            r.require("path");
            b.path = r.string("path", "");
        } else if (src == "blank") {
            b.source = BaseSource::Blank;
            b.height_m = r.numberIf("height_m", 0.0, [](double v) { return std::fabs(v) <= 1e5; }, "must be within +-100000");
        } else if (src == "fbm" || src == "diamond_square") {
            b.source = BaseSource::Fractal;
            b.fractal.kind = src == "fbm" ? FractalKind::Fbm : FractalKind::DiamondSquare;
            layers::readFractalFields(r, b.fractal);
        } else {
            r.fail("source", "must be synthesized, heightmap, blank, fbm or diamond_square");
        }
        if (r.has("band_cuts_px")) {
            const std::vector<double> cuts = r.numbers("band_cuts_px", 2, 2);
            if (cuts.size() == 2) {
                // Whole and within an image side before narrowing (an out-of-range double -> int is undefined).
                auto whole = [](double v) { return std::fabs(v) <= limits::kMaxImageSide && v == std::floor(v); };
                if (!whole(cuts[0]) || !whole(cuts[1])) {
                    r.fail("band_cuts_px", "must be integers within +-" + std::to_string(limits::kMaxImageSide));
                } else {
                    stack.bands.high_mid_cut_px = static_cast<int>(cuts[0]);
                    stack.bands.mid_low_cut_px = static_cast<int>(cuts[1]);
                    layers::adopt(r, validateBandSplit(stack.bands).withContext("band_cuts_px"));
                }
            }
        }
        b.weights = layers::readWeights(r, BandWeights{});
        if (Status s = r.finish(); !s) return s;
    }
    for (size_t i = first; i < layers.size(); ++i) {
        auto layer = layers::parseEditLayer(layers[i], "layers[" + std::to_string(i) + "]");
        if (!layer) return layer.status();
        stack.layers.push_back(std::move(*layer));
    }
    if (Status s = layers::checkStackSize(stack.layers); !s) return s;
    return stack;
}

// Evaluating a group recombines everything below it, so the cost grows with the number of layers
// and the depth of nesting: both are bounded (limits.h).
Status layers::checkStackSize(const std::vector<EditLayer>& layers) {
    size_t count = 0;
    std::function<Status(const std::vector<EditLayer>&, int, const std::string&)> visit =
        [&](const std::vector<EditLayer>& list, int depth, const std::string& where) -> Status {
        for (size_t i = 0; i < list.size(); ++i) {
            if (++count > static_cast<size_t>(limits::kMaxLayers))
                return Status::error("layers: more than " + std::to_string(limits::kMaxLayers) + " layers (groups' included)");
            const auto* group = std::get_if<GroupParams>(&list[i].tool);
            if (!group) continue;
            const std::string inner = where + "[" + std::to_string(i) + "].layers";
            if (depth + 1 > limits::kMaxGroupDepth)
                return Status::error(inner + ": groups nest more than " + std::to_string(limits::kMaxGroupDepth) + " deep");
            if (Status s = visit(group->children, depth + 1, inner); !s) return s;
        }
        return Status::ok();
    };
    return visit(layers, 0, "layers");
}

json layers::layerStackJson(const LayerStack& stack) {
    json out = json::array();
    out.push_back(layers::baseToJson(stack.base, stack.bands));
    for (const EditLayer& l : stack.layers) out.push_back(layers::editLayerToJson(l));
    return out;
}

Result<LayerStack> parseLayerStack(const std::string& layers_json, const std::string& base_dir) {
    auto layers = detail::parseJson(layers_json, "layers");
    if (!layers) return layers.status();
    return layers::parseLayerStackJson(*layers, base_dir);
}

std::string layerStackToJson(const LayerStack& stack) { return detail::dumpJson(layers::layerStackJson(stack)); }

Result<LayerStack> readLayerStack(const std::string& path) {
    auto text = readFileBytes(path, limits::kMaxJsonBytes);
    if (!text) return text.status();
    auto parsed = detail::parseJson(text.value(), path);
    if (!parsed) return parsed.status();
    const json& doc = *parsed;
    if (!doc.is_array() && !doc.is_object()) return Status::error(path + ": expected a project object or a layers array");
    const json layers = doc.is_array() ? doc : doc.value("layers", json::array());
    auto stack = layers::parseLayerStackJson(layers, detail::folderOf(path));
    if (!stack) return stack.status().withContext(path);
    return stack;
}

Status validateEditLayer(const EditLayer& layer, const std::string& context) {
    auto parsed = layers::parseEditLayer(layers::editLayerToJson(layer), context);
    return parsed ? Status::ok() : parsed.status();
}

}  // namespace terrasynth
