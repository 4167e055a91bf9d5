// The "constraints" section of a .tsyn project (docs/project-format.md): point and curve constraints,
// type painting and the freeze brush (as mask PNGs and/or brush strokes), pastes; in project pixels.
// constraintsToJson is the inverse of parseConstraints: painting comes back as masks.
#include "project/constraints_json.h"

#include <algorithm>
#include <cmath>

#include "constraints/curve_field.h"
#include "constraints/type_paint.h"
#include "core/json_reader.h"
#include "core/paths.h"
#include "terrasynth/constraints.h"
#include "terrasynth/database.h"
#include "terrasynth/heightfield_io.h"
#include "terrasynth/limits.h"

namespace terrasynth {
namespace {

using nlohmann::json;
using detail::JsonReader;

Result<uint8_t> typeByName(const ExemplarDatabase& db, const json& name, const std::string& path) {
    if (!name.is_string()) return Status::error(path + ": must be a terrain type name");
    const auto& names = db.type_names;
    auto it = std::find(names.begin(), names.end(), name.get<std::string>());
    if (it == names.end()) {
        std::string known;
        for (const auto& n : names) known += (known.empty() ? "" : ", ") + ("\"" + n + "\"");
        return Status::error(path + ": unknown terrain type \"" + name.get<std::string>() + "\" (database has " + known + ")");
    }
    return static_cast<uint8_t>(it - names.begin());
}

// Coordinates in the JSON are relative to the project's origin; both stay within +-2^28, so every
// site and course point is inside the +-2^29 grid that synthesis windows address (limits.h).
constexpr double kCoordinate = limits::kMaxConstraintCoordinate;

// `list` is an array of at most `limit` elements; the error names `path`.
Status checkArray(const json& list, const std::string& path, size_t limit, const char* what) {
    if (!list.is_array()) return Status::error(path + ": must be an array");
    if (list.size() > limit)
        return Status::error(path + ": " + std::to_string(list.size()) + " " + what + ", at most " + std::to_string(limit));
    return Status::ok();
}

Status parsePoints(const json& points, SynthesisConstraints& out, int64_t ox, int64_t oy) {
    if (Status s = checkArray(points, "constraints.points", limits::kMaxPointConstraints, "points"); !s) return s;
    for (size_t i = 0; i < points.size(); ++i) {
        JsonReader r(points[i], "constraints.points[" + std::to_string(i) + "]");
        PointConstraint c;
        c.x = ox + r.number("x", -kCoordinate, kCoordinate, std::nullopt);
        c.y = oy + r.number("y", -kCoordinate, kCoordinate, std::nullopt);
        c.height_m = static_cast<float>(r.number("height_m", -12000, 12000, std::nullopt));
        c.slope_direction_deg = static_cast<float>(r.number("slope_direction_deg", -360, 360, 0.0));
        c.slope_angle_deg = static_cast<float>(r.number("slope_angle_deg", 0, 80, 0.0));
        c.radius_px = static_cast<float>(r.number("radius_px", 1e-3, 1e6, 64.0));
        if (Status s = r.finish(); !s) return s;
        out.points.push_back(c);
    }
    return Status::ok();
}

// A list of `minimum`..`maximum` points [x, y] within +-2^28, offset by (ox, oy). The error names
// `path` (and the point).
Result<std::vector<std::pair<double, double>>> readPoints(const json& list, const std::string& path, size_t minimum,
                                                          size_t maximum, double ox = 0.0, double oy = 0.0) {
    if (!list.is_array() || list.size() < minimum || list.size() > maximum)
        return Status::error(path + ": must be an array of " + std::to_string(minimum) + ".." + std::to_string(maximum) +
                             " points [x, y]");
    std::vector<std::pair<double, double>> points;
    for (size_t i = 0; i < list.size(); ++i) {
        const json& p = list[i];
        if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number() ||
            !std::isfinite(p[0].get<double>()) || !std::isfinite(p[1].get<double>()))
            return Status::error(path + "[" + std::to_string(i) + "]: must be [x, y]");
        if (std::fabs(p[0].get<double>()) > kCoordinate || std::fabs(p[1].get<double>()) > kCoordinate)
            return Status::error(path + "[" + std::to_string(i) + "]: beyond +-2^28 pixels of the project origin");
        points.emplace_back(ox + p[0].get<double>(), oy + p[1].get<double>());
    }
    return points;
}

// One brush stroke {"radius_px": r, "points": [[x, y], ...]} painted with `value` (project pixels).
Status paintStrokeJson(JsonReader& r, uint8_t value, TypePaint& paint) {
    const double radius = r.number("radius_px", 0.5, 1e5, 16.0);
    const json* points = r.child("points");
    if (Status s = r.finish(); !s) return s;
    auto line = readPoints(points ? *points : json(), r.field("points"), 1, limits::kMaxStrokePoints,
                           static_cast<double>(paint.x), static_cast<double>(paint.y));
    if (!line) return line.status();
    const uint64_t cost = strokePaintCost(paint, line.value(), radius);
    if (cost > limits::kMaxStrokePaintCost)
        return Status::error(r.field("points") + ": painting this stroke would visit " + std::to_string(cost) +
                             " pixel rows, at most " + std::to_string(limits::kMaxStrokePaintCost) +
                             "; use fewer or shorter segments or a larger radius");
    paintStroke(paint, line.value(), radius, value);
    return Status::ok();
}

Status parseCurves(const json& curves, SynthesisConstraints& out, int64_t ox, int64_t oy) {
    if (Status s = checkArray(curves, "constraints.curves", limits::kMaxCurves, "curves"); !s) return s;
    for (size_t i = 0; i < curves.size(); ++i) {
        JsonReader r(curves[i], "constraints.curves[" + std::to_string(i) + "]");
        if (!r.ok()) return r.status();
        CurveConstraint curve;
        const json* course = r.child("course");
        auto points = readPoints(course ? *course : json(), r.field("course"), 2, limits::kMaxCoursePoints,
                                 static_cast<double>(ox), static_cast<double>(oy));
        if (!points) return points.status();
        curve.course = std::move(points.value());
        curve.spline = r.boolean("spline", true);
        const json* widgets = r.child("widgets");
        if (Status s = r.finish(); !s) return s;
        if (!widgets || !widgets->is_array() || widgets->empty() || widgets->size() > size_t(limits::kMaxCurveWidgets))
            return Status::error(r.field("widgets") + ": must be an array of 1.." +
                                 std::to_string(limits::kMaxCurveWidgets) + " widgets");
        for (size_t w = 0; w < widgets->size(); ++w) {
            JsonReader wr((*widgets)[w], r.field("widgets[" + std::to_string(w) + "]"));
            CurveWidget widget;
            widget.t = wr.number("t", 0, 1, std::nullopt);
            widget.height_m = static_cast<float>(wr.number("height_m", -12000, 12000, std::nullopt));
            widget.left_gradient = static_cast<float>(wr.number("left_gradient", -20, 20, 0.0));
            widget.right_gradient = static_cast<float>(wr.number("right_gradient", -20, 20, 0.0));
            widget.left_reach_px = static_cast<float>(wr.number("left_reach_px", 1e-3, 1e5, 32.0));
            widget.right_reach_px = static_cast<float>(wr.number("right_reach_px", 1e-3, 1e5, 32.0));
            if (Status s = wr.finish(); !s) return s;
            if (!curve.widgets.empty() && widget.t < curve.widgets.back().t)
                return Status::error(wr.field("t") + ": widgets must be sorted by t");
            curve.widgets.push_back(widget);
        }
        out.curves.push_back(std::move(curve));
    }
    // Together the courses are bounded in length and in crossings (cost limits, limits.h).
    return constraints::checkCurveLimits(out.curves, "constraints.curves");
}

// An 8-bit gray mask of the project's size, `field` naming it in errors.
Result<Image8> readExtentMask(const json& name, const std::string& field, const project::MaskReader& masks, int w, int h) {
    if (!name.is_string()) return Status::error(field + ": must be a PNG path");
    auto image = masks(name.get<std::string>());
    if (!image) return image.status().withContext(field);
    if (image->width != w || image->height != h || image->channels != 1)
        return Status::error(field + ": " + name.get<std::string>() + " must be 8-bit gray of the project size " +
                             std::to_string(w) + "x" + std::to_string(h));
    return image;
}

Status parseTypes(const json& types, const project::MaskReader& masks, const ExemplarDatabase& db, SynthesisConstraints& out,
                  int64_t ox, int64_t oy, int w, int h) {
    JsonReader r(types, "constraints.types");
    if (!r.ok()) return r.status();
    TypePaint& paint = out.types;
    paint.x = ox, paint.y = oy, paint.width = w, paint.height = h;
    paint.types.assign(static_cast<size_t>(w) * h, TypePaint::kUnpainted);
    const json* mask = r.child("mask");
    const json* palette = r.child("palette");
    const json* strokes = r.child("strokes");
    if (Status s = r.finish(); !s) return s;
    if (mask) {
        auto image = readExtentMask(*mask, "constraints.types.mask", masks, w, h);
        if (!image) return image.status();
        if (!palette || !palette->is_object())
            return Status::error("constraints.types.palette: must map mask values to type names");
        uint8_t lookup[256];
        std::fill(std::begin(lookup), std::end(lookup), TypePaint::kUnpainted);
        for (auto it = palette->begin(); it != palette->end(); ++it) {
            const std::string& key = it.key();
            const bool digits = !key.empty() && key.size() <= 3 && std::all_of(key.begin(), key.end(), ::isdigit);
            const int value = digits ? std::stoi(key) : -1;
            if (value < 1 || value > 255) return Status::error("constraints.types.palette: keys must be mask values 1..255");
            auto t = typeByName(db, it.value(), "constraints.types.palette." + key);
            if (!t) return t.status();
            lookup[value] = t.value();
        }
        for (size_t i = 0; i < paint.types.size(); ++i) paint.types[i] = lookup[image->samples[i]];
    }
    if (strokes) {
        if (Status s = checkArray(*strokes, "constraints.types.strokes", limits::kMaxStrokes, "strokes"); !s) return s;
        for (size_t i = 0; i < strokes->size(); ++i) {
            JsonReader sr((*strokes)[i], "constraints.types.strokes[" + std::to_string(i) + "]");
            if (!sr.ok()) return sr.status();
            auto type = typeByName(db, (*strokes)[i].value("type", json()), sr.field("type"));
            if (!type) return type.status();
            sr.use("type");
            if (Status painted = paintStrokeJson(sr, type.value(), paint); !painted) return painted;
        }
    }
    if (db.type_names.size() > static_cast<size_t>(kMaxPaintableTypes))
        return Status::error("constraints.types: painting needs a database of at most 32 types");
    return Status::ok();
}

// The freeze brush: an 8-bit mask PNG of the project's size (non-zero = frozen) and/or strokes.
Status parseFreeze(const json& freeze, const project::MaskReader& masks, SynthesisConstraints& out, int64_t ox, int64_t oy,
                   int w, int h) {
    JsonReader r(freeze, "constraints.freeze");
    if (!r.ok()) return r.status();
    TypePaint& mask = out.freeze;
    mask.x = ox, mask.y = oy, mask.width = w, mask.height = h;
    mask.types.assign(static_cast<size_t>(w) * h, 0);
    const json* image_name = r.child("mask");
    const json* strokes = r.child("strokes");
    if (Status s = r.finish(); !s) return s;
    if (image_name) {
        auto image = readExtentMask(*image_name, "constraints.freeze.mask", masks, w, h);
        if (!image) return image.status();
        for (size_t i = 0; i < mask.types.size(); ++i) mask.types[i] = image->samples[i] ? 1 : 0;
    }
    if (strokes) {
        if (Status s = checkArray(*strokes, "constraints.freeze.strokes", limits::kMaxStrokes, "strokes"); !s) return s;
        for (size_t i = 0; i < strokes->size(); ++i) {
            JsonReader sr((*strokes)[i], "constraints.freeze.strokes[" + std::to_string(i) + "]");
            if (!sr.ok()) return sr.status();
            if (Status painted = paintStrokeJson(sr, 1, mask); !painted) return painted;
        }
    }
    return Status::ok();
}

Status parsePastes(const json& pastes, const ExemplarDatabase& db, SynthesisConstraints& out, int64_t ox, int64_t oy) {
    if (Status s = checkArray(pastes, "constraints.pastes", limits::kMaxPastes, "pastes"); !s) return s;
    for (size_t i = 0; i < pastes.size(); ++i) {
        JsonReader r(pastes[i], "constraints.pastes[" + std::to_string(i) + "]");
        if (!r.ok()) return r.status();
        PasteConstraint paste;
        if (r.has("exemplar")) {
            const std::string name = r.string("exemplar", "");
            for (size_t k = 0; k < db.exemplars.size(); ++k)
                if (db.exemplars[k].name == name) paste.exemplar = static_cast<int>(k);
            if (r.ok() && paste.exemplar < 0) r.fail("exemplar", "no exemplar named \"" + name + "\"");
        }
        // Exemplar sources are in exemplar pixels; terrain sources in project pixels.
        const bool from_terrain = paste.exemplar < 0;
        const json* source = r.child("source");
        const std::vector<double> target = r.numbers("target", 2, 2);
        for (double v : target)
            if (std::fabs(v) > kCoordinate) r.fail("target", "beyond +-2^28 pixels of the project origin");
        paste.height_offset_m = static_cast<float>(r.number("height_offset_m", -12000, 12000, 0.0));
        if (Status s = r.finish(); !s) return s;
        auto points = readPoints(source ? *source : json(), r.field("source"), 3, limits::kMaxPastePolygonPoints,
                                 from_terrain ? static_cast<double>(ox) : 0.0, from_terrain ? static_cast<double>(oy) : 0.0);
        if (!points) return points.status();
        paste.source = std::move(points.value());
        paste.dx = ox + target[0] - paste.source[0].first;
        paste.dy = oy + target[1] - paste.source[0].second;
        out.pastes.push_back(std::move(paste));
    }
    return Status::ok();
}

// ---- The inverse ----

json pointsJson(const std::vector<std::pair<double, double>>& points, double ox, double oy) {
    json list = json::array();
    for (const auto& [x, y] : points) list.push_back({x - ox, y - oy});
    return list;
}

}  // namespace

project::MaskReader project::masksFromFolder(const std::string& base_dir) {
    return [base_dir](const std::string& name) { return readPng8(detail::resolveRelative(base_dir, name)); };
}

project::MaskReader project::masksFrom(const ConstraintsJson& written) {
    return [&written](const std::string& name) -> Result<Image8> {
        for (const ConstraintsJson::Mask& m : written.masks)
            if (detail::baseName(m.file) == name) return Image8{m.width, m.height, 1, m.pixels};
        return Status::error(name + ": no such mask");
    };
}

Result<SynthesisConstraints> parseConstraints(const std::string& text, const std::string& base_dir, const ExemplarDatabase& db,
                                              int64_t ox, int64_t oy, int w, int h) {
    auto parsed = detail::parseJson(text, "constraints");
    if (!parsed) return parsed.status();
    return project::parseConstraintsJson(*parsed, project::masksFromFolder(base_dir), db, ox, oy, w, h);
}

Result<SynthesisConstraints> project::parseConstraintsJson(const json& c, const MaskReader& masks, const ExemplarDatabase& db,
                                                         int64_t ox, int64_t oy, int w, int h) {
    SynthesisConstraints out;
    if (c.is_null()) return out;
    if (!c.is_object()) return Status::error("constraints: must be an object");
    for (auto it = c.begin(); it != c.end(); ++it)
        if (it.key() != "points" && it.key() != "types" && it.key() != "curves" && it.key() != "freeze" &&
            it.key() != "pastes")
            return Status::error("constraints." + it.key() + ": not supported (points, curves, types, freeze, pastes are)");
    if (auto p = c.find("points"); p != c.end())
        if (Status s = parsePoints(*p, out, ox, oy); !s) return s;
    if (auto curves = c.find("curves"); curves != c.end())
        if (Status s = parseCurves(*curves, out, ox, oy); !s) return s;
    if (auto t = c.find("types"); t != c.end())
        if (Status s = parseTypes(*t, masks, db, out, ox, oy, w, h); !s) return s;
    if (auto f = c.find("freeze"); f != c.end())
        if (Status s = parseFreeze(*f, masks, out, ox, oy, w, h); !s) return s;
    if (auto p = c.find("pastes"); p != c.end())
        if (Status s = parsePastes(*p, db, out, ox, oy); !s) return s;
    return out;
}

Result<ConstraintsJson> constraintsToJson(const SynthesisConstraints& c, const ExemplarDatabase& db, int64_t ox,
                                          int64_t oy, int w, int h, const std::string& mask_stem) {
    json j = json::object();
    const double x0 = static_cast<double>(ox), y0 = static_cast<double>(oy);
    ConstraintsJson out;
    if (!c.points.empty()) {
        json& points = j["points"] = json::array();
        for (const PointConstraint& p : c.points)
            points.push_back({{"x", p.x - x0}, {"y", p.y - y0}, {"height_m", p.height_m},
                              {"slope_direction_deg", p.slope_direction_deg}, {"slope_angle_deg", p.slope_angle_deg},
                              {"radius_px", p.radius_px}});
    }
    if (!c.curves.empty()) {
        json& curves = j["curves"] = json::array();
        for (const CurveConstraint& curve : c.curves) {
            json widgets = json::array();
            for (const CurveWidget& wd : curve.widgets)
                widgets.push_back({{"t", wd.t}, {"height_m", wd.height_m}, {"left_gradient", wd.left_gradient},
                                   {"right_gradient", wd.right_gradient}, {"left_reach_px", wd.left_reach_px},
                                   {"right_reach_px", wd.right_reach_px}});
            curves.push_back({{"course", pointsJson(curve.course, x0, y0)}, {"spline", curve.spline}, {"widgets", widgets}});
        }
    }
    if (!c.types.empty()) {
        // Mask value = type id + 1 (0 = unpainted), named through the palette.
        std::vector<uint8_t> pixels = constraints::paintOnWindow(c.types, {ox, oy, w, h}, TypePaint::kUnpainted);
        json palette = json::object();
        for (uint8_t& v : pixels) {
            if (v == TypePaint::kUnpainted) {
                v = 0;
                continue;
            }
            if (v >= db.type_names.size())
                return Status::error("constraints.types: type id " + std::to_string(v) + " is not in the database");
            palette[std::to_string(v + 1)] = db.type_names[v];
            v = static_cast<uint8_t>(v + 1);
        }
        out.masks.push_back({mask_stem + ".types.png", w, h, std::move(pixels)});
        j["types"] = {{"mask", detail::baseName(out.masks.back().file)}, {"palette", palette}};
    }
    if (!c.freeze.empty()) {
        std::vector<uint8_t> pixels = constraints::paintOnWindow(c.freeze, {ox, oy, w, h}, 0);
        for (uint8_t& v : pixels) v = v != 0 && v != TypePaint::kUnpainted ? 255 : 0;
        out.masks.push_back({mask_stem + ".freeze.png", w, h, std::move(pixels)});
        j["freeze"] = {{"mask", detail::baseName(out.masks.back().file)}};
    }
    if (!c.pastes.empty()) {
        json& pastes = j["pastes"] = json::array();
        for (const PasteConstraint& p : c.pastes) {
            if (p.source.empty()) return Status::error("constraints.pastes: a paste without a source polygon");
            const bool from_terrain = p.exemplar < 0;
            if (!from_terrain && p.exemplar >= static_cast<int>(db.exemplars.size()))
                return Status::error("constraints.pastes: exemplar " + std::to_string(p.exemplar) + " is not in the database");
            json paste = {{"source", from_terrain ? pointsJson(p.source, x0, y0) : pointsJson(p.source, 0.0, 0.0)},
                          {"target", {p.source[0].first + p.dx - x0, p.source[0].second + p.dy - y0}},
                          {"height_offset_m", p.height_offset_m}};
            if (!from_terrain) paste["exemplar"] = db.exemplars[p.exemplar].name;
            pastes.push_back(std::move(paste));
        }
    }
    out.json = j.dump();
    return out;
}

}  // namespace terrasynth
