// build_database() and write_heightmap(): `terrasynth db build`, and heightmaps from numpy arrays.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "terrasynth/database.h"
#include "terrasynth/gltf_export.h"

namespace terrasynth::python {

using namespace pybind11::literals;

void bindTools(py::module_& m) {
    m.def(
        "build_database",
        [](const std::vector<std::string>& exemplars, const std::string& out, int levels, double meters_per_pixel,
           int threads, const py::object& progress) {
            checkNumber("levels", levels, ranges::kDatabaseLevels);
            checkNumber("meters_per_pixel", meters_per_pixel, ranges::kDatabaseSpacing);
            checkNumber("threads", threads, ranges::kThreads);
            DatabaseBuildOptions options;
            options.levels = levels;
            options.meters_per_pixel = meters_per_pixel;
            options.threads = threads;
            // The first exception the callback raises is kept and raised when the build returns (the
            // build cannot stop half way; nor, for the same reason, can Ctrl-C stop it).
            std::optional<py::error_already_set> raised;
            if (!progress.is_none())
                options.progress = [&](const std::string& stage, double done) {
                    py::gil_scoped_acquire gil;
                    if (raised) return;
                    try {
                        progress(stage, done);
                    } catch (py::error_already_set& e) {
                        raised = std::move(e);
                    }
                };
            std::vector<std::pair<std::string, double>> voids;
            options.on_voids = [&](const ExemplarInfo& e, double share) { voids.emplace_back(e.path, share); };
            auto db = withoutGil([&]() -> Result<std::shared_ptr<const ExemplarDatabase>> {
                auto built = buildDatabase(exemplars, options);
                if (!built) return built;
                if (Status s = saveDatabase(*built.value(), out); !s) return s;
                return built;
            });
            if (raised) throw std::move(*raised);
            // Kept in a variable: the database lives as long as its only owner, this pointer.
            const std::shared_ptr<const ExemplarDatabase> built_db = take(std::move(db));
            const ExemplarDatabase& d = *built_db;
            std::vector<std::string> names;
            for (const ExemplarInfo& e : d.exemplars) names.push_back(e.name);
            return py::dict("path"_a = out, "exemplars"_a = names, "type_names"_a = d.type_names,
                            "levels"_a = d.levelCount(), "meters_per_pixel"_a = d.meters_per_pixel,
                            "bytes_per_base_pixel"_a = d.bytesPerBasePixel(), "void_shares"_a = voids);
        },
        "exemplars"_a, "out"_a, py::kw_only(), "levels"_a = 6, "meters_per_pixel"_a = 0.0, "threads"_a = 0,
        "progress"_a = py::none(),
        "Builds the exemplar database (Gain et al. s4) of exemplar files or folders (16-bit PNG + JSON "
        "sidecar, .f32 + sidecar, or any GDAL raster) and writes it to `out` (.tsdb), as `terrasynth db "
        "build` does: levels L (levels 0..L), meters_per_pixel the common spacing (0: the coarsest "
        "exemplar's), threads (0: all cores). progress(stage, fraction) is called as it goes. Deterministic: "
        "the same inputs give the same bytes. Returns what it built (exemplars, type_names, levels, "
        "meters_per_pixel, bytes_per_base_pixel, void_shares).");
    m.def(
        "write_heightmap",
        [](const std::string& path, const py::array_t<float, py::array::c_style | py::array::forcecast>& heights,
           double spacing, std::tuple<int64_t, int64_t> origin) {
            if (heights.ndim() != 2) throw py::value_error("heights: expected a 2-D array (rows north to south)");
            checkNumber("spacing", spacing, NumberRange{1e-6, 1e5});
            const auto& [x, y] = origin;
            const PixelWindow window = checkedWindow(x, y, heights.shape(1), heights.shape(0));
            Heightfield field(window.width, window.height, spacing);
            std::copy(heights.data(), heights.data() + field.size(), field.heights.begin());
            check(withoutGil([&] { return exportHeightmap(path, field, window); }));
        },
        "path"_a, "heights"_a, "spacing"_a, py::kw_only(), "origin"_a = std::tuple<int64_t, int64_t>{0, 0},
        "Writes a 2-D array of heights in metres (row 0 north) spaced `spacing` metres apart, the format from "
        "the extension as Project.export_heightmap; `origin` (x, y) is the global pixel of its north-west "
        "sample, which places a GeoTIFF in the world frame.");
}

}  // namespace terrasynth::python
