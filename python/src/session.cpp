// terrasynth.Session: the terrain being edited (terrasynth::EditSession), as the editor's edit thread
// drives it: constraints, type paint, layers, undo, and a save the editor and `terrasynth synth` read.
#include <memory>
#include <mutex>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "arrays.h"
#include "bindings.h"
#include "exports.h"
#include "terrasynth/edit_session.h"
#include "terrasynth/layers.h"

namespace terrasynth::python {
namespace {

using namespace pybind11::literals;
using Points = py::array_t<double, py::array::c_style | py::array::forcecast>;
using Changed = std::optional<WindowTuple>;

// An EditSession is for one thread at a time; Python threads may share this object, so every call
// takes the lock (after the GIL is released, so a waiting call never blocks Python).
struct Session {
    std::unique_ptr<EditSession> edit;
    std::mutex mutex;

    template <class Call>
    auto locked(Call&& call) {
        return withoutGil([&] {
            std::lock_guard<std::mutex> lock(mutex);
            return call(*edit);
        });
    }
    template <class Call>
    Changed change(Call&& call) {
        return windowTuple(take(locked(std::forward<Call>(call))));
    }
};

CurveWidget widgetFrom(const py::dict& d, size_t index) {
    CurveWidget w;
    const std::string field = "widgets[" + std::to_string(index) + "]";
    for (const auto& [key, value] : d) {
        const std::string k = py::str(key);
        const double v = value.cast<double>();
        if (k == "t") w.t = v;
        else if (k == "height_m") w.height_m = static_cast<float>(v);
        else if (k == "left_gradient") w.left_gradient = static_cast<float>(v);
        else if (k == "right_gradient") w.right_gradient = static_cast<float>(v);
        else if (k == "left_reach_px") w.left_reach_px = static_cast<float>(v);
        else if (k == "right_reach_px") w.right_reach_px = static_cast<float>(v);
        else
            throw py::value_error(field + ": unknown key '" + k +
                                  "' (t, height_m, left_gradient, right_gradient, left_reach_px, right_reach_px)");
    }
    return w;
}

// One edit layer in the project's JSON (docs/layers.md), from a dict or its JSON text, parsed by the
// runtime exactly as a project's "layers" array is.
EditLayer layerFrom(const py::object& layer, const std::string& folder) {
    const std::string text =
        py::isinstance<py::str>(layer) ? layer.cast<std::string>() : py::module_::import("json").attr("dumps")(layer).cast<std::string>();
    LayerStack stack = take(parseLayerStack("[" + text + "]", folder));
    if (stack.layers.size() != 1) throw py::value_error("layer: expected one edit layer (not a base), got " + text);
    return std::move(stack.layers.front());
}

ExportInput exportInput(Session& s) {
    ExportInput in;
    in.extent = s.edit->extent();
    in.heights = s.edit->heightSource();  // the world as it is now, safe from any thread
    return in;
}

}  // namespace

void bindSession(py::module_& m) {
    py::class_<Session> session(m, "Session",
        "A project being edited, as the in-engine editor edits it (runtime EditSession): every edit is one "
        "undo step, re-synthesizing only what it reaches (s5.3); save() writes the .tsyn and the "
        "edited-heights sidecar the editor writes. Coordinates are level-0 pixels of the global grid (x east, "
        "y south), heights metres. Edits that change heights return the changed window (x, y, width, height), "
        "or None. One call at a time (others wait); the GIL is released meanwhile.");
    session
        .def_property_readonly("path", [](Session& s) { return s.edit->project().path; },
                               "The project file it was opened from or last saved to.")
        .def_property_readonly("spacing", [](Session& s) { return s.edit->frame().meters_per_pixel; },
                               "Metres between level-0 samples.")
        .def_property_readonly("extent", [](Session& s) { return *windowTuple(s.edit->extent()); },
                               "The edited extent (x, y, width, height), level-0 pixels.")
        .def_property_readonly("seed", [](Session& s) { return s.edit->project().synthesis.seed; },
                               "The synthesis seed (reseed() changes it).")
        .def_property_readonly("type_names", [](Session& s) { return s.edit->database().type_names; },
                               "Terrain type names, for paint_types().")
        .def_property_readonly("warnings", [](Session& s) { return s.edit->warnings(); },
                               "What went wrong but was recovered from while opening (also given as UserWarnings).")
        .def_property_readonly("is_dirty", [](Session& s) { return s.edit->isDirty(); },
                               "Whether anything changed since the last save or open.")
        .def_property_readonly("can_undo", [](Session& s) { return s.locked([](EditSession& e) { return e.canUndo(); }); },
                               "Whether undo() has a step to undo.")
        .def_property_readonly("can_redo", [](Session& s) { return s.locked([](EditSession& e) { return e.canRedo(); }); },
                               "Whether redo() has a step to redo.")
        .def_property_readonly("point_ids", [](Session& s) { return s.locked([](EditSession& e) { return e.pointIds(); }); },
                               "Ids of the point constraints, in list order (new ids after reopening).")
        .def_property_readonly("curve_ids", [](Session& s) { return s.locked([](EditSession& e) { return e.curveIds(); }); },
                               "Ids of the curve constraints, in list order.")
        .def_property_readonly(
            "layers",
            [](Session& s) {
                const std::string text = s.locked([](EditSession& e) { return layerStackToJson(e.layers()); });
                return py::module_::import("json").attr("loads")(text);
            },
            "The layer stack as the project's 'layers' JSON array (docs/layers.md), base first.")
        .def(
            "heights",
            [](Session& s, std::optional<int64_t> x, std::optional<int64_t> y, std::optional<int64_t> width,
               std::optional<int64_t> height, int level) {
                const PixelWindow window = requestedWindow(s.edit->extent(), x, y, width, height, level);
                const HeightSource world = s.edit->heightSource();
                return heightsArray(take(withoutGil([&] { return world(window, level); })));
            },
            "x"_a = py::none(), "y"_a = py::none(), "width"_a = py::none(), "height"_a = py::none(), py::kw_only(),
            "level"_a = 0,
            "Heights (float32, shape (height, width)) of a window of the world as edited so far; all four left "
            "out: the extent. Around the extent the world is the synthesis the session opened with.")
        .def(
            "add_point",
            [](Session& s, double x, double y, double height_m, double radius_px, double slope_angle_deg,
               double slope_direction_deg) {
                PointConstraint p;
                p.x = x, p.y = y;
                p.height_m = static_cast<float>(height_m);
                p.radius_px = static_cast<float>(radius_px);
                p.slope_angle_deg = static_cast<float>(slope_angle_deg);
                p.slope_direction_deg = static_cast<float>(slope_direction_deg);
                EditId id = 0;
                take(s.locked([&](EditSession& e) { return e.addPoint(p, &id); }));
                return id;
            },
            "x"_a, "y"_a, "height_m"_a, py::kw_only(), "radius_px"_a = 64.0, "slope_angle_deg"_a = 0.0,
            "slope_direction_deg"_a = 0.0,
            "Adds a point constraint (s5.1): the terrain at pixel (x, y) reaches height_m, rising at "
            "slope_angle_deg (0..80) towards slope_direction_deg (clockwise from north), over radius_px. "
            "Returns its id.")
        .def("move_point", [](Session& s, EditId id, double x, double y) {
            return s.change([&](EditSession& e) { return e.movePoint(id, x, y); });
        }, "id"_a, "x"_a, "y"_a, "Moves point `id` to pixel (x, y).")
        .def("remove_point", [](Session& s, EditId id) {
            return s.change([&](EditSession& e) { return e.removePoint(id); });
        }, "id"_a, "Removes point `id`.")
        .def(
            "add_curve",
            [](Session& s, const Points& course, const std::vector<py::dict>& widgets, bool spline) {
                CurveConstraint c;
                c.course = pairsFrom(course, "course");
                c.spline = spline;
                for (size_t i = 0; i < widgets.size(); ++i) c.widgets.push_back(widgetFrom(widgets[i], i));
                EditId id = 0;
                take(s.locked([&](EditSession& e) { return e.addCurve(c, &id); }));
                return id;
            },
            "course"_a, "widgets"_a, py::kw_only(), "spline"_a = true,
            "Adds a curve constraint (s5.1): a course, an (N, 2) array of pixels (a Catmull-Rom spline through "
            "them unless spline=False), and widgets sorted by t, dicts of t (0..1 along the course), height_m, "
            "left_gradient, right_gradient (rise in m/m away from the curve), left_reach_px, right_reach_px "
            "(docs/curves.md). Returns its id.")
        .def("remove_curve", [](Session& s, EditId id) {
            return s.change([&](EditSession& e) { return e.removeCurve(id); });
        }, "id"_a, "Removes curve `id`.")
        .def(
            "paint_types",
            [](Session& s, const Points& stroke, double radius_px, const std::string& type_name) {
                const auto line = pairsFrom(stroke, "stroke");
                return s.change([&](EditSession& e) { return e.paintTypes(line, radius_px, type_name); });
            },
            "stroke"_a, "radius_px"_a, "type_name"_a,
            "Paints terrain type `type_name` (one of type_names) with a round brush along `stroke`, an (N, 2) "
            "array of pixels (s5.2).")
        .def(
            "erase_types",
            [](Session& s, const Points& stroke, double radius_px) {
                const auto line = pairsFrom(stroke, "stroke");
                return s.change([&](EditSession& e) { return e.eraseTypes(line, radius_px); });
            },
            "stroke"_a, "radius_px"_a, "Makes the pixels along `stroke` unpainted again.")
        .def(
            "freeze",
            [](Session& s, const Points& stroke, double radius_px) {
                const auto line = pairsFrom(stroke, "stroke");
                return s.change([&](EditSession& e) { return e.freeze(line, radius_px); });
            },
            "stroke"_a, "radius_px"_a, "Freezes the pixels along `stroke`: later edits keep their heights (s5.3).")
        .def(
            "unfreeze",
            [](Session& s, const Points& stroke, double radius_px) {
                const auto line = pairsFrom(stroke, "stroke");
                return s.change([&](EditSession& e) { return e.unfreeze(line, radius_px); });
            },
            "stroke"_a, "radius_px"_a, "Unfreezes the pixels along `stroke`.")
        .def(
            "add_layer",
            [](Session& s, const py::object& layer, int index) {
                EditLayer parsed = layerFrom(layer, s.edit->project().folder());
                return s.change([&](EditSession& e) { return e.addLayer(std::move(parsed), index); });
            },
            "layer"_a, "index"_a = -1,
            "Adds an edit layer (Bradbury et al. 2014) given as in a project's 'layers' array (docs/layers.md), "
            "a dict or its JSON text, e.g. {'type': 'peak', 'center': [300, 260], 'height_m': 900, "
            "'spread_px': 30}; its geometry is in pixels of the extent (0, 0 = its north-west corner). "
            "index -1 puts it on top.")
        .def("remove_layer", [](Session& s, int index) {
            return s.change([&](EditSession& e) { return e.removeLayer(index); });
        }, "index"_a, "Removes edit layer `index` (0 = the bottom one above the base).")
        .def("set_layer_visible", [](Session& s, int index, bool visible) {
            return s.change([&](EditSession& e) { return e.setLayerVisible(index, visible); });
        }, "index"_a, "visible"_a, "Shows or hides edit layer `index`.")
        .def(
            "reseed",
            [](Session& s, int64_t seed) {
                checkNumber("seed", static_cast<double>(seed), ranges::kSeed);
                return s.change([&](EditSession& e) { return e.reseed(static_cast<uint32_t>(seed)); });
            },
            "seed"_a, "Synthesizes the extent afresh with a new seed (constraints and layers kept).")
        .def("undo", [](Session& s) { return s.change([](EditSession& e) { return e.undo(); }); },
             "Undoes the last edit, bit for bit; returns the changed window, None when there was nothing to undo.")
        .def("redo", [](Session& s) { return s.change([](EditSession& e) { return e.redo(); }); },
             "Redoes the last undone edit, bit for bit; None when there was nothing to redo.")
        .def(
            "save",
            [](Session& s, std::optional<std::string> path) {
                const std::string target = path ? *path : s.edit->project().path;
                if (target.empty()) throw py::value_error("save: the session has no file yet; give a path");
                check(s.locked([&](EditSession& e) { return e.save(target); }));
            },
            "path"_a = py::none(),
            "Writes the project (.tsyn), its mask PNGs and its edited-heights sidecar, all or nothing, as the "
            "editor saves; default: the file it was opened from (or last saved to).");
    addExportMethods(session, [](Session& s) { return exportInput(s); });

    m.def(
        "edit",
        [](const std::string& path, const std::string& backend, const std::string& device, int max_undo_steps) {
            checkNumber("max_undo_steps", max_undo_steps, NumberRange{1, 256});
            EditSessionOptions options;
            options.synthesizer = synthesizerOptions(backend, device);
            options.max_undo_steps = max_undo_steps;
            auto s = std::make_unique<Session>();
            s->edit = take(withoutGil([&] { return EditSession::open(path, options); }));
            warnEach(s->edit->warnings());
            return s;
        },
        "path"_a, py::kw_only(), "backend"_a = "opencl", "device"_a = "", "max_undo_steps"_a = 100,
        "Opens a .tsyn project for editing (as terrasynth_editor does). backend and device as for open().");
}

}  // namespace terrasynth::python
