// osgdb_terrasynth: the osgDB entry point for .tsyn projects. Everything real lives in
// terrasynth_plugin (TerrainNode) and the runtime (Terrain); this file only maps osgDB's calling
// convention onto them and never lets an exception or a foreign file through.
#include <algorithm>
#include <exception>
#include <memory>
#include <string>

#include <osg/Notify>
#include <osgDB/FileNameUtils>
#include <osgDB/FileUtils>
#include <osgDB/Registry>

#include "terrasynth/gltf_export.h"
#include "terrasynth/guard.h"
#include "terrasynth/project.h"
#include "terrasynth/terrain.h"
#include "terrasynth_plugin/plugin_options.h"
#include "terrasynth_plugin/terrain_node.h"

namespace {

using namespace terrasynth;
using namespace terrasynth::plugin;

// The coarsest level whose tiles over the project extent are at most 16: a cheap, whole first view.
int automaticPreloadLevel(const Project& p, const TerrainNodeOptions& o) {
    for (int level = o.min_level; level < o.max_level; ++level) {
        const int64_t span = static_cast<int64_t>(o.tile_size) << level;
        const int64_t nx = (p.origin_x + p.width - 1) / span - p.origin_x / span + 1;
        const int64_t ny = (p.origin_y + p.height - 1) / span - p.origin_y / span + 1;
        if (nx * ny <= 16) return level;
    }
    return o.max_level;
}

// The terrain type of every sample: the default type of the exemplar its synthesized pixel came from.
TypeSource terrainTypeSource(std::shared_ptr<Terrain> terrain) {
    return [terrain](const PixelWindow& w, int level) -> Result<std::vector<uint8_t>> {
        auto out = terrain->synthesize(w, level, /*want_sources=*/true);
        if (!out) return out.status();
        return typesFromSources(out->source_exemplar, terrain->database().exemplar_type);
    };
}

// Tints spread over the preloaded extent's heights, fog just inside the draw radius, then the options.
TerrainLook lookFor(const TerrainNode& node, const PixelWindow& extent, const PluginOptions& o) {
    const auto range = node.heightRange(extent);
    TerrainLook look = range ? lookForHeightRange(range->first, range->second) : TerrainLook{};
    look.fog_visibility_m = static_cast<float>(0.9 * node.options().view_radius_m);
    if (o.sun_azimuth_deg) look.sun_azimuth_deg = *o.sun_azimuth_deg;
    if (o.sun_elevation_deg) look.sun_elevation_deg = *o.sun_elevation_deg;
    if (o.fog_m) look.fog_visibility_m = *o.fog_m;
    if (o.snow_line_m) {
        const float shift = *o.snow_line_m - look.snow_line_m;
        look.snow_line_m += shift;
        look.alpine_m = std::min(look.alpine_m, look.snow_line_m);
        look.lowland_top_m = std::min(look.lowland_top_m, look.alpine_m);
    }
    if (o.type_colors) look.type_colour_mix = 0.45f;
    return look;
}

class ReaderWriterTerrasynth : public osgDB::ReaderWriter {
public:
    ReaderWriterTerrasynth() {
        supportsExtension("tsyn", "terrasynth project (terrain synthesis by example)");
        supportsOption("tileSize=<n>", "quads per tile side (default 256)");
        supportsOption("maxLevel=<n>", "level of the root tiles (default 5, clamped to the database)");
        supportsOption("minLevel=<n>", "finest level drawn (default 0)");
        supportsOption("meshStep=<n>", "grid step in samples (default 1)");
        supportsOption("pixelError=<px>", "screen-space error that triggers refinement (default 8)");
        supportsOption("viewRadius=<m>", "draw radius around the eye (default one root tile)");
        supportsOption("threads=<n>", "worker threads (default hardware threads)");
        supportsOption("cacheMB=<MiB>", "resident tile budget (default 768)");
        supportsOption("mergesPerFrame=<n>", "tiles attached per frame at most (default 16)");
        supportsOption("mergeBudgetMs=<ms>", "main-thread merge time per frame (default 2)");
        supportsOption("skirt=<spacings>", "extra skirt depth in sample spacings (default 2)");
        supportsOption("geomorph=<0|1>", "blend tiles towards their parent before it takes over (default 1)");
        supportsOption("seed=<n>", "override the project's synthesis seed");
        supportsOption("backend=<opencl|reference>", "synthesizer backend");
        supportsOption("device=<name>", "OpenCL device substring");
        supportsOption("preload=<0|1>", "build the project extent before returning (default 1)");
        supportsOption("preloadLevel=<n>", "level of the preload (default automatic)");
        supportsOption("sunAzimuth=<deg>", "fixed sun azimuth, clockwise from north (default 315)");
        supportsOption("sunElevation=<deg>", "fixed sun elevation (default 40)");
        supportsOption("snowLine=<m>", "snow above this height (default from the project's heights)");
        supportsOption("fog=<m>", "distance of 95% fog (default 0.9 x draw radius, 0 = none)");
        supportsOption("typeColors=<0|1>", "colour painted terrain types (default 0)");
    }

    const char* className() const override { return "terrasynth .tsyn terrain reader"; }

    // osgconv and osgDB::readObjectFile ask for an object: the terrain node is one.
    ReadResult readObject(const std::string& file, const Options* options) const override {
        return readNode(file, options);
    }

    ReadResult readNode(const std::string& file, const Options* options) const override {
        // osgDB calls in from any thread: nothing may escape (terrasynth/guard.h).
        return invokeGuarded([&] { return read(file, options); },
                             [&](const std::string& why) { return ReadResult("terrasynth: " + file + ": " + why); });
    }

private:
    ReadResult read(const std::string& file, const Options* options) const {
        if (!acceptsExtension(osgDB::getLowerCaseFileExtension(file))) return ReadResult::FILE_NOT_HANDLED;
        const std::string path = osgDB::findDataFile(file, options);
        if (path.empty()) return ReadResult::FILE_NOT_FOUND;

        auto parsed = parsePluginOptions(options ? options->getOptionString() : std::string());
        if (!parsed) return ReadResult(path + ": " + parsed.message());
        PluginOptions opts = std::move(*parsed);

        auto project = loadProject(path);
        if (!project) return ReadResult(project.message());
        if (opts.seed) project->synthesis.seed = *opts.seed;
        TerrainOptions terrain_options;
        terrain_options.synthesizer = opts.synthesizer;
        terrain_options.on_warning = [](const std::string& warning) { OSG_WARN << "terrasynth: " << warning << std::endl; };
        auto terrain = Terrain::fromProject(*project, terrain_options);
        if (!terrain) return ReadResult(path + ": " + terrain.message());
        std::shared_ptr<Terrain> shared = *terrain;
        // Clamped to the database loaded, not to the project's database_levels: a prebuilt
        // database has the levels it has, whatever the project says.
        if (!opts.max_level_given) opts.node.max_level = clampedMaxLevel(opts.node, shared->database().levelCount());

        // A project read from a file does not change under the node: tiles share their group's
        // synthesis (height_source.h).
        HeightSource source = tileGroupedSource(
            [shared](const PixelWindow& w, int level) { return shared->heights(w, level); }, opts.node.tile_size);
        osg::ref_ptr<TerrainNode> node = new TerrainNode(source, shared->metersPerPixel(0), opts.node);
        node->setName(osgDB::getSimpleFileName(path));
        if (opts.type_colors) node->setTypeSource(terrainTypeSource(shared));
        // Every worker's synthesizer now, before a window exists. Made on first use, a worker was
        // still creating its own (PoCL context, program, database upload) when osgviewer closed
        // its window after a 20-frame run, and the process aborted in Mesa's glXDestroyContext
        // with a corrupted heap: about 1 run in 3 on 2 cores, none in 14 since.
        if (Status s = node->runOnEveryWorker([&] { return shared->prepareThisThread(); }); !s)
            return ReadResult(path + ": " + s.message());
        if (opts.preload) {
            const int level = opts.preload_level >= 0 ? opts.preload_level
                                                      : automaticPreloadLevel(shared->project(), opts.node);
            // Roots first (the first frame draws from them), then the level that osgconv writes.
            for (int l : {opts.node.max_level, level}) {
                if (Status s = node->preload(shared->extent(), l); !s) return ReadResult(path + ": " + s.message());
                if (l == level) break;
            }
            node->setHomeExtent(shared->extent());
        }
        node->setLook(lookFor(*node, shared->extent(), opts));
        return node.get();
    }
};

}  // namespace

REGISTER_OSGPLUGIN(terrasynth, ReaderWriterTerrasynth)
