// The worker-side tile job: the data model (heights, types), then the mesh and the detached OSG node.
#include "tile_builder.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "terrasynth/guard.h"

namespace terrasynth::plugin {
namespace {

double msSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

std::string keyName(const TileKey& k) {
    return "tile " + std::to_string(k.level) + "/" + std::to_string(k.x) + "/" + std::to_string(k.y);
}

// Height range of the meshed samples (apron excluded).
HeightRange innerRange(const Heightfield& f, int border) {
    HeightRange r{f.at(border, border), f.at(border, border)};
    for (int y = border; y < f.height - border; ++y)
        for (int x = border; x < f.width - border; ++x) {
            const float h = f.at(x, y);
            r.min = std::min(r.min, h);
            r.max = std::max(r.max, h);
        }
    return r;
}

// Type id per vertex from the tile's types (width x width samples, row-major): the sample under the
// vertex; skirt vertices hang below a border sample and take its type.
std::vector<float> vertexTypes(const TileMesh& mesh, const std::vector<uint8_t>& types, int width, double spacing) {
    std::vector<float> out(mesh.vertexCount());
    for (size_t v = 0; v < out.size(); ++v) {
        const int64_t col = std::clamp<int64_t>(std::llround(mesh.positions[3 * v] / spacing), 0, width - 1);
        const int64_t row = std::clamp<int64_t>(std::llround(-mesh.positions[3 * v + 1] / spacing), 0, width - 1);
        out[v] = types[static_cast<size_t>(row * width + col)];
    }
    return out;
}

// The data model: the tile's window plus apron from `source`, and its types when there is a type
// source. Wrong-sized answers are errors naming the tile.
Result<TileData> readTileData(const HeightSource& source, const TileKey& key, const TileBuildSettings& s,
                              const TypeSource* types) {
    const PixelWindow window = tileReadWindow(key, s);
    Result<Heightfield> heights = source(window, key.level);
    if (!heights) return heights.status().withContext(keyName(key));
    if (heights->width != window.width || heights->height != window.height)
        return Status::error(keyName(key) + ": height source returned " + std::to_string(heights->width) + "x" +
                             std::to_string(heights->height) + " samples for a " + std::to_string(window.width) +
                             "x" + std::to_string(window.height) + " window");
    TileData data;
    data.key = key;
    data.heights = std::move(*heights);
    data.apron = s.mesh_step;
    data.mesh_step = s.mesh_step;
    data.spacing_m = s.layout.spacing(key.level);
    data.west_x = s.layout.westX(key);
    data.north_y = s.layout.northY(key);
    if (types && *types) {
        const PixelWindow tw = s.layout.window(key);
        Result<std::vector<uint8_t>> ids = (*types)(tw, key.level);
        if (!ids) return ids.status().withContext(keyName(key) + " (types)");
        if (ids->size() != static_cast<size_t>(tw.width) * tw.height)
            return Status::error(keyName(key) + ": type source returned a wrong-sized window");
        data.types = std::move(*ids);
    }
    const HeightRange range = innerRange(data.heights, data.apron);
    data.min_height = range.min;
    data.max_height = range.max;
    // The types are part of what is drawn: a rebuild whose heights are equal but whose types differ
    // (an editor's painting overlay) must still be swapped in.
    data.hash = hashTileData(data.heights, data.types);
    return Result<TileData>(std::move(data));
}

TileBuild buildTileUnguarded(const HeightSource& source, const TileKey& key, const TileBuildSettings& s,
                             const TileData* parent, const TypeSource* types) {
    TERRASYNTH_REQUIRE(s.mesh_step >= 1 && s.layout.tile_size % s.mesh_step == 0,
                       "tile_size must be a positive multiple of mesh_step");
    TERRASYNTH_REQUIRE(!s.geomorph || (s.layout.tile_size / s.mesh_step) % 2 == 0,
                       "geomorphing needs an even number of quads per tile side");
    TileBuild out;
    out.key = key;

    // 1. The data model: heights of the tile plus its apron, types.
    auto t0 = std::chrono::steady_clock::now();
    Result<TileData> read = readTileData(source, key, s, types);
    out.heights_ms = msSince(t0);
    if (!read) {
        out.status = read.status();
        return out;
    }
    auto data = std::make_shared<const TileData>(std::move(*read));

    // 2. Mesh relative to the tile corner; skirts deep enough to hide any LOD step (see settings).
    t0 = std::chrono::steady_clock::now();
    MeshOptions mo;
    mo.step = s.mesh_step;
    mo.border = s.mesh_step;
    mo.skirt_depth_m = (data->max_height - data->min_height) +
                       s.skirt_extra_spacings * static_cast<float>(s.layout.spacing(key.level));
    mo.optimize_order = s.optimize_order;
    const TileMesh mesh = meshHeightfield(data->heights, mo);
    out.mesh_ms = msSince(t0);

    // 3. Geomorph targets: the parent level's samples under this tile (bit-identical to the
    // parent's own, so tiles sharing an edge morph to the same heights).
    std::vector<float> coarse;
    HeightRange coarse_range{data->min_height, data->max_height};
    if (s.geomorph && key.level < s.max_level) {
        const int half = s.layout.tile_size / 2;
        Heightfield parent_samples;
        if (parent) {
            TERRASYNTH_REQUIRE(parent->tileSize() == s.layout.tile_size, "the parent tile has other settings");
            parent_samples = parentSamples(*parent, key);
        } else {
            t0 = std::chrono::steady_clock::now();
            const PixelWindow pw{key.x * half, key.y * half, half + 1, half + 1};
            Result<Heightfield> from_source = source(pw, key.level + 1);
            out.heights_ms += msSince(t0);
            if (!from_source) {
                out.status = from_source.status().withContext(keyName(key) + " (parent level)");
                return out;
            }
            if (from_source->width != pw.width || from_source->height != pw.height) {
                out.status = Status::error(keyName(key) + ": height source returned a wrong-sized parent window");
                return out;
            }
            parent_samples = std::move(*from_source);
        }
        coarse = parentSurfaceHeights(mesh, parent_samples, s.layout.spacing(key.level), s.mesh_step, mo.skirt_depth_m);
        coarse_range = {*std::min_element(coarse.begin(), coarse.end()), *std::max_element(coarse.begin(), coarse.end())};
    }

    // 4. Terrain types per vertex for type colours (optional).
    std::vector<float> type_ids;
    if (!data->types.empty())
        type_ids = vertexTypes(mesh, data->types, s.layout.tile_size + 1, s.layout.spacing(key.level));

    // 5. The detached render model.
    t0 = std::chrono::steady_clock::now();
    const double wx = data->west_x, ny = data->north_y;
    out.node = makeTileNode(mesh, wx, ny, &out.bytes, coarse.empty() ? nullptr : &coarse,
                            s.layout.spacing(key.level + 1), type_ids.empty() ? nullptr : &type_ids);
    out.triangles = mesh.triangleCount();
    const double span = s.layout.tileMeters(key.level);
    out.box.set(wx, ny - span, std::min(data->min_height, coarse_range.min) - mo.skirt_depth_m, wx + span, ny,
                std::max(data->max_height, coarse_range.max));
    out.osg_ms = msSince(t0);
    out.data = std::move(data);
    return out;
}

}  // namespace

PixelWindow tileReadWindow(const TileKey& key, const TileBuildSettings& s) {
    PixelWindow w = s.layout.window(key);
    const int apron = s.mesh_step;
    return {w.x - apron, w.y - apron, w.width + 2 * apron, w.height + 2 * apron};
}

TileBuild buildTile(const HeightSource& source, const TileKey& key, const TileBuildSettings& s,
                    const TileData* parent, const TypeSource* types) {
    // Tiles build on worker threads: anything thrown (out of memory, OSG) becomes the tile's error.
    return invokeGuarded([&] { return buildTileUnguarded(source, key, s, parent, types); },
                         [&](const std::string& why) {
                             TileBuild failed;
                             failed.key = key;
                             failed.status = Status::error(keyName(key) + ": " + why);
                             return failed;
                         });
}

}  // namespace terrasynth::plugin
