// The worker-side tile job: heights, mesh, detached OSG node.
#include "terrasynth_plugin/tile_builder.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
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

// Type id per vertex from the tile window's types (width x width samples, row-major): the sample
// under the vertex; skirt vertices hang below a border sample and take its type.
std::vector<float> vertexTypes(const TileMesh& mesh, const std::vector<uint8_t>& types, int width, double spacing) {
    std::vector<float> out(mesh.vertexCount());
    for (size_t v = 0; v < out.size(); ++v) {
        const int64_t col = std::clamp<int64_t>(std::llround(mesh.positions[3 * v] / spacing), 0, width - 1);
        const int64_t row = std::clamp<int64_t>(std::llround(-mesh.positions[3 * v + 1] / spacing), 0, width - 1);
        out[v] = types[static_cast<size_t>(row * width + col)];
    }
    return out;
}

}  // namespace

uint64_t hashHeights(const Heightfield& field) {
    uint64_t h = 1469598103934665603ull;
    auto mix = [&h](const void* data, size_t n) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
    };
    mix(&field.width, sizeof field.width);
    mix(&field.height, sizeof field.height);
    mix(field.heights.data(), field.heights.size() * sizeof(float));
    return h;
}

PixelWindow tileReadWindow(const TileKey& key, const TileBuildSettings& s) {
    PixelWindow w = s.layout.window(key);
    const int apron = s.mesh_step;
    return {w.x - apron, w.y - apron, w.width + 2 * apron, w.height + 2 * apron};
}

namespace {

TileBuild buildTileUnguarded(const HeightSource& source, const TileKey& key, const TileBuildSettings& s,
                             const Heightfield* parent_samples, const TypeSource* types) {
    TERRASYNTH_REQUIRE(s.mesh_step >= 1 && s.layout.tile_size % s.mesh_step == 0,
                       "tile_size must be a positive multiple of mesh_step");
    TERRASYNTH_REQUIRE(!s.geomorph || (s.layout.tile_size / s.mesh_step) % 2 == 0,
                       "geomorphing needs an even number of quads per tile side");
    TileBuild out;
    out.key = key;

    // 1. Heights of the tile plus its apron.
    auto t0 = std::chrono::steady_clock::now();
    const PixelWindow window = tileReadWindow(key, s);
    Result<Heightfield> heights = source(window, key.level);
    out.heights_ms = msSince(t0);
    if (!heights) {
        out.status = heights.status().withContext(keyName(key));
        return out;
    }
    const Heightfield& field = *heights;
    if (field.width != window.width || field.height != window.height) {
        out.status = Status::error(keyName(key) + ": height source returned " + std::to_string(field.width) + "x" +
                                   std::to_string(field.height) + " samples for a " +
                                   std::to_string(window.width) + "x" + std::to_string(window.height) + " window");
        return out;
    }
    out.heights_hash = hashHeights(field);
    const HeightRange range = innerRange(field, s.mesh_step);
    out.min_height = range.min;
    out.max_height = range.max;

    // 2. Mesh relative to the tile corner; skirts deep enough to hide any LOD step (see settings).
    t0 = std::chrono::steady_clock::now();
    MeshOptions mo;
    mo.step = s.mesh_step;
    mo.border = s.mesh_step;
    mo.skirt_depth_m = (range.max - range.min) +
                       s.skirt_extra_spacings * static_cast<float>(s.layout.spacing(key.level));
    mo.optimize_order = s.optimize_order;
    const TileMesh mesh = meshHeightfield(field, mo);
    out.mesh_ms = msSince(t0);

    // 3. Geomorph targets: the parent level's samples under this tile (bit-identical to the
    // parent's own, so tiles sharing an edge morph to the same heights).
    std::vector<float> coarse;
    HeightRange coarse_range = range;
    if (s.geomorph && key.level < s.max_level) {
        const int half = s.layout.tile_size / 2;
        const PixelWindow pw{key.x * half, key.y * half, half + 1, half + 1};
        Result<Heightfield> parent = Status::error("unset");
        if (parent_samples && parent_samples->width == pw.width && parent_samples->height == pw.height) {
            parent = *parent_samples;
        } else {
            t0 = std::chrono::steady_clock::now();
            parent = source(pw, key.level + 1);
            out.heights_ms += msSince(t0);
            if (!parent) {
                out.status = parent.status().withContext(keyName(key) + " (parent level)");
                return out;
            }
            if (parent->width != pw.width || parent->height != pw.height) {
                out.status = Status::error(keyName(key) + ": height source returned a wrong-sized parent window");
                return out;
            }
        }
        coarse = parentSurfaceHeights(mesh, *parent, s.layout.spacing(key.level), s.mesh_step, mo.skirt_depth_m);
        coarse_range = {*std::min_element(coarse.begin(), coarse.end()), *std::max_element(coarse.begin(), coarse.end())};
    }

    // 4. Terrain types for type colours (optional).
    std::vector<float> type_ids;
    if (types && *types) {
        t0 = std::chrono::steady_clock::now();
        const PixelWindow tw = s.layout.window(key);
        Result<std::vector<uint8_t>> ids = (*types)(tw, key.level);
        out.heights_ms += msSince(t0);
        if (!ids) {
            out.status = ids.status().withContext(keyName(key) + " (types)");
            return out;
        }
        if (ids->size() != static_cast<size_t>(tw.width) * tw.height) {
            out.status = Status::error(keyName(key) + ": type source returned a wrong-sized window");
            return out;
        }
        type_ids = vertexTypes(mesh, *ids, tw.width, s.layout.spacing(key.level));
        // The types are part of what is drawn: a rebuild whose heights are equal but whose types
        // differ (an editor's painting overlay) must still be swapped in.
        for (uint8_t id : *ids) out.heights_hash = (out.heights_hash ^ id) * 1099511628211ull;
    }

    // 5. The detached render model.
    t0 = std::chrono::steady_clock::now();
    const double wx = s.layout.westX(key), ny = s.layout.northY(key);
    out.node = makeTileNode(mesh, wx, ny, &out.bytes, coarse.empty() ? nullptr : &coarse,
                            s.layout.spacing(key.level + 1), type_ids.empty() ? nullptr : &type_ids);
    out.triangles = mesh.triangleCount();
    const double span = s.layout.tileMeters(key.level);
    out.box.set(wx, ny - span, std::min(range.min, coarse_range.min) - mo.skirt_depth_m, wx + span, ny,
                std::max(range.max, coarse_range.max));
    out.osg_ms = msSince(t0);
    return out;
}

}  // namespace

TileBuild buildTile(const HeightSource& source, const TileKey& key, const TileBuildSettings& s,
                    const Heightfield* parent_samples, const TypeSource* types) {
    // Tiles build on worker threads: anything thrown (out of memory, OSG) becomes the tile's error.
    return invokeGuarded([&] { return buildTileUnguarded(source, key, s, parent_samples, types); },
                         [&](const std::string& why) {
                             TileBuild failed;
                             failed.key = key;
                             failed.status = Status::error(keyName(key) + ": " + why);
                             return failed;
                         });
}

}  // namespace terrasynth::plugin
