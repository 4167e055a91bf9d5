// The "constraints" section of a .tsyn project (docs/project-format.md): point constraints and
// type painting (as a mask PNG with a palette, or as brush strokes), in project pixels.
#include <algorithm>
#include <cmath>
#include <optional>

#include "core/sidecar.h"
#include "terrasynth/constraints.h"
#include "terrasynth/database.h"
#include "terrasynth/heightfield_io.h"

namespace terrasynth {
namespace {

using nlohmann::json;

// A checked number field "<path>.<key>"; `fallback` when absent, else an error.
Result<double> number(const json& object, const char* key, const std::string& path, double lo, double hi,
                      std::optional<double> fallback = std::nullopt) {
    auto v = detail::readNumberInRange(object, key, path + "." + key, lo, hi);
    if (!v) return v.status();
    if (v.value()) return *v.value();
    if (fallback) return *fallback;
    return Status::error(path + "." + key + ": missing");
}

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

Status parsePoints(const json& points, SynthesisConstraints& out, int64_t ox, int64_t oy) {
    if (!points.is_array()) return Status::error("constraints.points: must be an array");
    for (size_t i = 0; i < points.size(); ++i) {
        const std::string path = "constraints.points[" + std::to_string(i) + "]";
        const json& p = points[i];
        if (!p.is_object()) return Status::error(path + ": must be an object");
        PointConstraint c;
        auto x = number(p, "x", path, -1e8, 1e8), y = number(p, "y", path, -1e8, 1e8);
        auto h = number(p, "height_m", path, -12000, 12000);
        auto dir = number(p, "slope_direction_deg", path, -360, 360, 0.0);
        auto angle = number(p, "slope_angle_deg", path, 0, 80, 0.0);
        auto radius = number(p, "radius_px", path, 1e-3, 1e6, 64.0);
        for (auto* r : {&x, &y, &h, &dir, &angle, &radius})
            if (!*r) return r->status();
        c.x = ox + x.value();
        c.y = oy + y.value();
        c.height_m = static_cast<float>(h.value());
        c.slope_direction_deg = static_cast<float>(dir.value());
        c.slope_angle_deg = static_cast<float>(angle.value());
        c.radius_px = static_cast<float>(radius.value());
        out.points.push_back(c);
    }
    return Status::ok();
}

// Paints a round brush of `radius` pixels along each segment of a stroke.
void paintStroke(TypePaint& paint, const std::vector<std::pair<double, double>>& line, double radius, uint8_t type) {
    auto dab = [&](double cx, double cy) {
        for (int y = static_cast<int>(std::floor(cy - radius)); y <= static_cast<int>(std::ceil(cy + radius)); ++y)
            for (int x = static_cast<int>(std::floor(cx - radius)); x <= static_cast<int>(std::ceil(cx + radius)); ++x)
                if (x >= 0 && y >= 0 && x < paint.width && y < paint.height && (x - cx) * (x - cx) + (y - cy) * (y - cy) <= radius * radius)
                    paint.types[static_cast<size_t>(y) * paint.width + x] = type;
    };
    for (size_t i = 0; i < line.size(); ++i) {
        if (i == 0) dab(line[0].first, line[0].second);
        if (i == 0) continue;
        const double dx = line[i].first - line[i - 1].first, dy = line[i].second - line[i - 1].second;
        const int steps = std::max(1, static_cast<int>(std::ceil(std::hypot(dx, dy) / std::max(0.5, radius * 0.5))));
        for (int s = 1; s <= steps; ++s) dab(line[i - 1].first + dx * s / steps, line[i - 1].second + dy * s / steps);
    }
}

// A list of [x, y] points (at least `minimum`), offset by (ox, oy). The error names `path`.
Result<std::vector<std::pair<double, double>>> readPoints(const json& list, const std::string& path, size_t minimum,
                                                          double ox = 0.0, double oy = 0.0) {
    if (!list.is_array() || list.size() < minimum)
        return Status::error(path + ": must be an array of at least " + std::to_string(minimum) + " points [x, y]");
    std::vector<std::pair<double, double>> points;
    for (const json& p : list) {
        if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number())
            return Status::error(path + ": each point must be [x, y]");
        points.emplace_back(ox + p[0].get<double>(), oy + p[1].get<double>());
    }
    return points;
}

// One brush stroke {"radius_px": r, "points": [[x, y], ...]} painted with `value`.
Status paintStrokeJson(const json& stroke, const std::string& path, uint8_t value, TypePaint& paint) {
    if (!stroke.is_object()) return Status::error(path + ": must be an object");
    auto radius = number(stroke, "radius_px", path, 0.5, 1e5, 16.0);
    if (!radius) return radius.status();
    auto line = readPoints(stroke.value("points", json()), path + ".points", 1);
    if (!line) return line.status();
    paintStroke(paint, line.value(), radius.value(), value);
    return Status::ok();
}

std::string resolvePath(const std::string& base_dir, const std::string& name) {
    return !name.empty() && name.front() == '/' ? name : base_dir + "/" + name;
}

Status parseCurves(const json& curves, SynthesisConstraints& out, int64_t ox, int64_t oy) {
    if (!curves.is_array()) return Status::error("constraints.curves: must be an array");
    for (size_t i = 0; i < curves.size(); ++i) {
        const std::string path = "constraints.curves[" + std::to_string(i) + "]";
        const json& c = curves[i];
        if (!c.is_object()) return Status::error(path + ": must be an object");
        CurveConstraint curve;
        auto course = readPoints(c.value("course", json()), path + ".course", 2, static_cast<double>(ox), static_cast<double>(oy));
        if (!course) return course.status();
        curve.course = std::move(course.value());
        if (auto spline = c.find("spline"); spline != c.end()) {
            if (!spline->is_boolean()) return Status::error(path + ".spline: must be true or false");
            curve.spline = spline->get<bool>();
        }
        auto widgets = c.find("widgets");
        if (widgets == c.end() || !widgets->is_array() || widgets->empty())
            return Status::error(path + ".widgets: must be a non-empty array");
        for (size_t w = 0; w < widgets->size(); ++w) {
            const std::string wp = path + ".widgets[" + std::to_string(w) + "]";
            const json& j = (*widgets)[w];
            if (!j.is_object()) return Status::error(wp + ": must be an object");
            CurveWidget widget;
            auto t = number(j, "t", wp, 0, 1);
            auto h = number(j, "height_m", wp, -12000, 12000);
            auto lg = number(j, "left_gradient", wp, -20, 20, 0.0), rg = number(j, "right_gradient", wp, -20, 20, 0.0);
            auto lr = number(j, "left_reach_px", wp, 1e-3, 1e5, 32.0), rr = number(j, "right_reach_px", wp, 1e-3, 1e5, 32.0);
            for (auto* r : {&t, &h, &lg, &rg, &lr, &rr})
                if (!*r) return r->status();
            widget.t = t.value();
            widget.height_m = static_cast<float>(h.value());
            widget.left_gradient = static_cast<float>(lg.value()), widget.right_gradient = static_cast<float>(rg.value());
            widget.left_reach_px = static_cast<float>(lr.value()), widget.right_reach_px = static_cast<float>(rr.value());
            if (!curve.widgets.empty() && widget.t < curve.widgets.back().t)
                return Status::error(wp + ".t: widgets must be sorted by t");
            curve.widgets.push_back(widget);
        }
        out.curves.push_back(std::move(curve));
    }
    return Status::ok();
}


Status parseTypes(const json& types, const std::string& base_dir, const ExemplarDatabase& db, SynthesisConstraints& out,
                  int64_t ox, int64_t oy, int w, int h) {
    if (!types.is_object()) return Status::error("constraints.types: must be an object");
    TypePaint& paint = out.types;
    paint.x = ox, paint.y = oy, paint.width = w, paint.height = h;
    paint.types.assign(static_cast<size_t>(w) * h, TypePaint::kUnpainted);
    if (auto mask = types.find("mask"); mask != types.end()) {
        if (!mask->is_string()) return Status::error("constraints.types.mask: must be a PNG path");
        const std::string path = resolvePath(base_dir, mask->get<std::string>());
        auto image = readPng8(path);
        if (!image) return image.status().withContext("constraints.types.mask");
        if (image->width != w || image->height != h || image->channels != 1)
            return Status::error("constraints.types.mask: " + path + " must be 8-bit gray of the project size " +
                                 std::to_string(w) + "x" + std::to_string(h));
        auto palette = types.find("palette");
        if (palette == types.end() || !palette->is_object())
            return Status::error("constraints.types.palette: must map mask values to type names");
        uint8_t lookup[256];
        std::fill(std::begin(lookup), std::end(lookup), TypePaint::kUnpainted);
        for (auto it = palette->begin(); it != palette->end(); ++it) {
            int value = -1;
            try { value = std::stoi(it.key()); } catch (...) {}
            if (value < 1 || value > 255) return Status::error("constraints.types.palette: keys must be mask values 1..255");
            auto t = typeByName(db, it.value(), "constraints.types.palette." + it.key());
            if (!t) return t.status();
            lookup[value] = t.value();
        }
        for (size_t i = 0; i < paint.types.size(); ++i) paint.types[i] = lookup[image->samples[i]];
    }
    if (auto strokes = types.find("strokes"); strokes != types.end()) {
        if (!strokes->is_array()) return Status::error("constraints.types.strokes: must be an array");
        for (size_t i = 0; i < strokes->size(); ++i) {
            const std::string path = "constraints.types.strokes[" + std::to_string(i) + "]";
            const json& stroke = (*strokes)[i];
            auto type = typeByName(db, stroke.is_object() ? stroke.value("type", json()) : json(), path + ".type");
            if (!type) return type.status();
            Status painted = paintStrokeJson(stroke, path, type.value(), paint);
            if (!painted) return painted;
        }
    }
    if (db.type_names.size() > static_cast<size_t>(kMaxPaintableTypes))
        return Status::error("constraints.types: painting needs a database of at most 32 types");
    return Status::ok();
}

// The freeze brush: an 8-bit mask PNG of the project's size (non-zero = frozen) and/or strokes.
Status parseFreeze(const json& freeze, const std::string& base_dir, SynthesisConstraints& out, int64_t ox, int64_t oy,
                   int w, int h) {
    if (!freeze.is_object()) return Status::error("constraints.freeze: must be an object");
    TypePaint& mask = out.freeze;
    mask.x = ox, mask.y = oy, mask.width = w, mask.height = h;
    mask.types.assign(static_cast<size_t>(w) * h, 0);
    if (auto m = freeze.find("mask"); m != freeze.end()) {
        if (!m->is_string()) return Status::error("constraints.freeze.mask: must be a PNG path");
        const std::string path = resolvePath(base_dir, m->get<std::string>());
        auto image = readPng8(path);
        if (!image) return image.status().withContext("constraints.freeze.mask");
        if (image->width != w || image->height != h || image->channels != 1)
            return Status::error("constraints.freeze.mask: " + path + " must be 8-bit gray of the project size");
        for (size_t i = 0; i < mask.types.size(); ++i) mask.types[i] = image->samples[i] ? 1 : 0;
    }
    if (auto strokes = freeze.find("strokes"); strokes != freeze.end()) {
        if (!strokes->is_array()) return Status::error("constraints.freeze.strokes: must be an array");
        for (size_t i = 0; i < strokes->size(); ++i) {
            Status painted = paintStrokeJson((*strokes)[i], "constraints.freeze.strokes[" + std::to_string(i) + "]", 1, mask);
            if (!painted) return painted;
        }
    }
    return Status::ok();
}

Status parsePastes(const json& pastes, const ExemplarDatabase& db, SynthesisConstraints& out, int64_t ox, int64_t oy) {
    if (!pastes.is_array()) return Status::error("constraints.pastes: must be an array");
    for (size_t i = 0; i < pastes.size(); ++i) {
        const std::string path = "constraints.pastes[" + std::to_string(i) + "]";
        const json& p = pastes[i];
        if (!p.is_object()) return Status::error(path + ": must be an object");
        PasteConstraint paste;
        if (auto e = p.find("exemplar"); e != p.end()) {
            if (!e->is_string()) return Status::error(path + ".exemplar: must be an exemplar name");
            for (size_t k = 0; k < db.exemplars.size(); ++k)
                if (db.exemplars[k].name == e->get<std::string>()) paste.exemplar = static_cast<int>(k);
            if (paste.exemplar < 0) return Status::error(path + ".exemplar: no exemplar named \"" + e->get<std::string>() + "\"");
        }
        // Exemplar sources are in exemplar pixels; terrain sources in project pixels.
        const bool from_terrain = paste.exemplar < 0;
        auto source = readPoints(p.value("source", json()), path + ".source", 3, from_terrain ? ox : 0, from_terrain ? oy : 0);
        if (!source) return source.status();
        paste.source = std::move(source.value());
        auto target = p.find("target");
        if (target == p.end() || !target->is_array() || target->size() != 2 || !(*target)[0].is_number() ||
            !(*target)[1].is_number())
            return Status::error(path + ".target: must be [x, y], where the source's first point lands");
        paste.dx = ox + (*target)[0].get<double>() - paste.source[0].first;
        paste.dy = oy + (*target)[1].get<double>() - paste.source[0].second;
        auto offset = number(p, "height_offset_m", path, -12000, 12000, 0.0);
        if (!offset) return offset.status();
        paste.height_offset_m = static_cast<float>(offset.value());
        out.pastes.push_back(std::move(paste));
    }
    return Status::ok();
}

}  // namespace

Result<SynthesisConstraints> parseConstraints(const json& c, const std::string& base_dir, const ExemplarDatabase& db,
                                              int64_t ox, int64_t oy, int w, int h) {
    SynthesisConstraints out;
    if (c.is_null()) return out;
    if (!c.is_object()) return Status::error("constraints: must be an object");
    for (auto it = c.begin(); it != c.end(); ++it)
        if (it.key() != "points" && it.key() != "types" && it.key() != "curves" && it.key() != "freeze" &&
            it.key() != "pastes")
            return Status::error("constraints." + it.key() + ": not supported (points, curves, types, freeze, pastes are)");
    if (auto p = c.find("points"); p != c.end()) {
        Status s = parsePoints(*p, out, ox, oy);
        if (!s) return s;
    }
    if (auto curves = c.find("curves"); curves != c.end()) {
        Status s = parseCurves(*curves, out, ox, oy);
        if (!s) return s;
    }
    if (auto t = c.find("types"); t != c.end()) {
        Status s = parseTypes(*t, base_dir, db, out, ox, oy, w, h);
        if (!s) return s;
    }
    if (auto f = c.find("freeze"); f != c.end()) {
        Status s = parseFreeze(*f, base_dir, out, ox, oy, w, h);
        if (!s) return s;
    }
    if (auto p = c.find("pastes"); p != c.end()) {
        Status s = parsePastes(*p, db, out, ox, oy);
        if (!s) return s;
    }
    return out;
}

}  // namespace terrasynth
