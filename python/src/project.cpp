// terrasynth.Project: a project opened for height queries (terrasynth::Terrain), what `terrasynth
// synth` and `terrasynth export` read.
#include <algorithm>
#include <memory>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "arrays.h"
#include "bindings.h"
#include "exports.h"
#include "terrasynth/gltf_export.h"
#include "terrasynth/terrain.h"

namespace terrasynth::python {
namespace {

using namespace pybind11::literals;
using TerrainPtr = std::shared_ptr<Terrain>;
using Size = std::tuple<int64_t, int64_t>;

// Overrides of a project's settings, as `terrasynth synth` takes them on its command line.
struct Overrides {
    std::optional<int64_t> seed;
    std::optional<Size> size, origin;
    std::optional<std::string> drainage;
    std::optional<bool> relax_offsets;
};

void applyOverrides(Project& project, const Overrides& o) {
    if (o.seed) {
        checkNumber("seed", static_cast<double>(*o.seed), ranges::kSeed);
        project.synthesis.seed = static_cast<uint32_t>(*o.seed);
    }
    if (o.size) {
        const auto& [width, height] = *o.size;
        checkNumber("size[0]", static_cast<double>(width), ranges::kWindowSide);
        checkNumber("size[1]", static_cast<double>(height), ranges::kWindowSide);
        project.width = static_cast<int>(width), project.height = static_cast<int>(height);
    }
    if (o.origin) std::tie(project.origin_x, project.origin_y) = *o.origin;  // checkProjectExtent bounds them
    if (o.drainage) {
        if (*o.drainage == "off") project.synthesis.drainage = Drainage::Off;
        else if (*o.drainage == "breach") project.synthesis.drainage = Drainage::Breach;
        else throw py::value_error("drainage: expected 'off' or 'breach', got '" + *o.drainage + "'");
    }
    if (o.relax_offsets) project.synthesis.relax_offsets = *o.relax_offsets;
}

TerrainPtr openTerrain(Project project, const Overrides& overrides, const std::string& backend,
                       const std::string& device) {
    applyOverrides(project, overrides);
    TerrainOptions options;
    options.synthesizer = synthesizerOptions(backend, device);
    TerrainPtr terrain = take(withoutGil([&] { return Terrain::fromProject(std::move(project), options); }));
    warnEach(terrain->warnings());
    return terrain;
}

// As `terrasynth export` reads a project. The sources are called during the export call only, while
// the Python object holds the terrain.
ExportInput exportInput(Terrain& terrain) {
    Terrain* t = &terrain;
    ExportInput in;
    in.extent = t->extent();
    in.heights = [t](const PixelWindow& w, int level) { return t->heights(w, level); };
    in.types = [t](const PixelWindow& w, int level) -> Result<std::vector<uint8_t>> {
        auto out = t->synthesize(w, level, /*want_sources=*/true);
        if (!out) return out.status();
        return typesFromSources(out->source_exemplar, t->database().exemplar_type);
    };
    in.type_names = t->database().type_names;
    return in;
}

SynthesisOutput synthesized(Terrain& t, std::optional<int64_t> x, std::optional<int64_t> y,
                            std::optional<int64_t> width, std::optional<int64_t> height, int level, bool sources) {
    const PixelWindow window = requestedWindow(t.extent(), x, y, width, height, level);
    return take(withoutGil([&] { return t.synthesize(window, level, sources); }));
}

const char* kWindowArgs =
    "x, y, width, height: a window of the global pixel grid at `level` (x east, y south; level 0 = full "
    "resolution, level k spaced 2^k times as far); all four left out: the project's extent at that level.";

}  // namespace

void bindProject(py::module_& m) {
    py::class_<Terrain, TerrainPtr> project(m, "Project",
        "A terrasynth project opened for height queries: the terrain `terrasynth synth` writes, with its "
        "constraints, layers and edited heights. Thread-safe: calls from several Python threads run in "
        "parallel (the GIL is released while the runtime works).");
    project
        .def_property_readonly("path", [](const Terrain& t) { return t.project().path; },
                               "The project file ('' for a project made by from_database).")
        .def_property_readonly("spacing", [](const Terrain& t) { return t.metersPerPixel(0); },
                               "Metres between level-0 samples (level k: spacing * 2**k).")
        .def_property_readonly("extent", [](const Terrain& t) { return *windowTuple(t.extent()); },
                               "The project's extent (x, y, width, height) in level-0 pixels of the global grid.")
        .def_property_readonly("seed", [](const Terrain& t) { return t.project().synthesis.seed; },
                               "The synthesis seed (the project's, or open()'s seed).")
        .def_property_readonly("type_names", [](const Terrain& t) { return t.database().type_names; },
                               "Terrain type names; types() returns indices into this list (255: none).")
        .def_property_readonly("exemplar_names", [](const Terrain& t) {
            std::vector<std::string> names;
            for (const ExemplarInfo& e : t.database().exemplars) names.push_back(e.name);
            return names;
        }, "The database's exemplars; sources() returns indices into this list.")
        .def_property_readonly("uses_edited_heights", &Terrain::usesEditedHeights,
                               "Whether the extent's heights come from the edited-heights sidecar an edit session saved.")
        .def_property_readonly("warnings", &Terrain::warnings,
                               "What went wrong but was recovered from while opening (also given as UserWarnings).")
        .def(
            "heights",
            [](Terrain& t, std::optional<int64_t> x, std::optional<int64_t> y, std::optional<int64_t> width,
               std::optional<int64_t> height, int level) {
                return heightsArray(std::move(synthesized(t, x, y, width, height, level, false).heights));
            },
            "x"_a = py::none(), "y"_a = py::none(), "width"_a = py::none(), "height"_a = py::none(), py::kw_only(),
            "level"_a = 0,
            (std::string("Final heights in metres, a float32 array of shape (height, width), row 0 north: bit "
                         "for bit what `terrasynth synth` writes for that window. ") + kWindowArgs)
                .c_str())
        .def(
            "sources",
            [](Terrain& t, std::optional<int64_t> x, std::optional<int64_t> y, std::optional<int64_t> width,
               std::optional<int64_t> height, int level) {
                SynthesisOutput out = synthesized(t, x, y, width, height, level, true);
                const int rows = out.heights.height, cols = out.heights.width;
                return py::make_tuple(toArray(std::move(out.source_x), rows, cols),
                                      toArray(std::move(out.source_y), rows, cols),
                                      toArray(std::move(out.source_exemplar), rows, cols));
            },
            "x"_a = py::none(), "y"_a = py::none(), "width"_a = py::none(), "height"_a = py::none(), py::kw_only(),
            "level"_a = 0,
            (std::string("Where each pixel was copied from, as `terrasynth synth --sources` maps it: (source_x, "
                         "source_y, exemplar), float32 exemplar pixels at that level and uint8 indices into "
                         "exemplar_names, each of shape (height, width). ") + kWindowArgs)
                .c_str())
        .def(
            "types",
            [](Terrain& t, std::optional<int64_t> x, std::optional<int64_t> y, std::optional<int64_t> width,
               std::optional<int64_t> height, int level) {
                SynthesisOutput out = synthesized(t, x, y, width, height, level, true);
                const int rows = out.heights.height, cols = out.heights.width;
                return toArray(typesFromSources(out.source_exemplar, t.database().exemplar_type), rows, cols);
            },
            "x"_a = py::none(), "y"_a = py::none(), "width"_a = py::none(), "height"_a = py::none(), py::kw_only(),
            "level"_a = 0,
            (std::string("Terrain type per pixel (uint8 indices into type_names, 255 = none), shape (height, "
                         "width): what `terrasynth export --masks` splits into masks. ") + kWindowArgs)
                .c_str())
        .def(
            "heights_at",
            [](Terrain& t, const py::array_t<double, py::array::c_style | py::array::forcecast>& points) {
                const auto world = pointsFrom(points, "points");
                std::vector<double> h = take(withoutGil([&] { return t.heightsAt(world); }));
                return py::array_t<double>(static_cast<py::ssize_t>(h.size()), h.data());
            },
            "points"_a,
            "Level-0 heights (float64, metres) at world points, an (N, 2) array of x east, y north in metres "
            "(pixel (x, y) lies at (x * spacing, -y * spacing)), bilinear between the four samples around each.");
    addExportMethods(project, [](Terrain& t) { return exportInput(t); });

    m.def(
        "open",
        [](const std::string& path, std::optional<int64_t> seed, std::optional<Size> size, std::optional<Size> origin,
           std::optional<std::string> drainage, std::optional<bool> relax_offsets, const std::string& backend,
           const std::string& device) {
            Project project = take(withoutGil([&] { return loadProject(path); }));
            return openTerrain(std::move(project), {seed, size, origin, drainage, relax_offsets}, backend, device);
        },
        "path"_a, py::kw_only(), "seed"_a = py::none(), "size"_a = py::none(), "origin"_a = py::none(),
        "drainage"_a = py::none(), "relax_offsets"_a = py::none(), "backend"_a = "opencl", "device"_a = "",
        "Opens a .tsyn project (building its database cache beside it when missing or stale). The keywords "
        "override the project's settings as `terrasynth synth`'s flags do: seed, size (width, height), "
        "origin (x, y) of the extent's north-west pixel, drainage ('breach' or 'off'), relax_offsets. backend: "
        "'opencl' (the first OpenCL device, or `device`, a substring of its name) or 'reference' (plain C++). "
        "Raises terrasynth.Error with the runtime's message (naming the file and the problem).");
    m.def(
        "from_database",
        [](const std::string& database, Size size, Size origin, int64_t seed, std::optional<std::string> drainage,
           std::optional<bool> relax_offsets, const std::string& backend, const std::string& device) {
            Project project;
            project.database = database;
            return openTerrain(std::move(project), {seed, size, origin, drainage, relax_offsets}, backend, device);
        },
        "database"_a, "size"_a, py::kw_only(), "origin"_a = Size{0, 0}, "seed"_a = 1, "drainage"_a = py::none(),
        "relax_offsets"_a = py::none(), "backend"_a = "opencl", "device"_a = "",
        "A project of no file over a prebuilt database (.tsdb, see build_database): `terrasynth synth --db "
        "DATABASE --size WxH --seed N` as an object. size (width, height) and origin (x, y) give the extent; "
        "the other keywords are those of open().");
}

PixelWindow requestedWindow(const PixelWindow& extent, std::optional<int64_t> x, std::optional<int64_t> y,
                            std::optional<int64_t> width, std::optional<int64_t> height, int level) {
    checkNumber("level", level, ranges::kOutputLevel);
    if (x && y && width && height) return checkedWindow(*x, *y, *width, *height);
    if (x || y || width || height) throw py::value_error("give all of x, y, width, height, or none of them (the extent)");
    PixelWindow window = extent;  // the extent at a coarser level covers the same ground
    window.x >>= level, window.y >>= level;
    window.width = std::max(1, window.width >> level), window.height = std::max(1, window.height >> level);
    return window;
}

void warnEach(const std::vector<std::string>& warnings) {
    for (const std::string& w : warnings)
        if (PyErr_WarnEx(PyExc_UserWarning, w.c_str(), 1) < 0) throw py::error_already_set();
}

}  // namespace terrasynth::python
