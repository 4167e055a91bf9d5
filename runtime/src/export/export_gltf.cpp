// exportGltf: fetch heights band by band -> mesh each tile's LOD chain -> pick the shared packing
// frame from the global height range -> pack tiles -> optional texture -> tinygltf model -> files.
#include <tiny_gltf.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>
#include <thread>

#include "export/colors.h"
#include "core/paths.h"
#include "export/export_internal.h"
#include "terrasynth/guard.h"

namespace terrasynth {

using namespace export_detail;

namespace {

Status checkOptions(const GltfExportOptions& o) {
    if (o.region.width < 2 || o.region.height < 2)
        return Status::error("region: needs at least 2x2 samples, got " + std::to_string(o.region.width) + "x" +
                             std::to_string(o.region.height));
    if (o.region.width > 65536 || o.region.height > 65536) return Status::error("region: at most 65536 samples per side");
    if (o.tile_size < 1 || o.tile_size > 4096) return Status::error("tile_size: must be 1..4096, got " + std::to_string(o.tile_size));
    if (o.lods < 1 || o.lods > 8) return Status::error("lods: must be 1..8, got " + std::to_string(o.lods));
    if (o.texture_size < 0 || o.texture_size > 8192)
        return Status::error("texture_size: must be 0..8192, got " + std::to_string(o.texture_size));
    if (o.level < 0) return Status::error("level: must not be negative");
    // Every tile is a glTF node with its own meshes: bound the count before allocating them.
    const int64_t tiles = int64_t((o.region.width - 2) / o.tile_size + 1) * ((o.region.height - 2) / o.tile_size + 1);
    if (tiles > kMaxGltfTiles)
        return Status::error("tile_size: " + std::to_string(o.tile_size) + " cuts the region into " + std::to_string(tiles) +
                             " tiles, at most " + std::to_string(kMaxGltfTiles) + "; use larger tiles");
    return Status::ok();
}

Heightfield cropField(const Heightfield& f, int x0, int y0, int w, int h) {
    Heightfield out(w, h, f.meters_per_pixel_x);
    out.meters_per_pixel_y = f.meters_per_pixel_y;
    for (int y = 0; y < h; ++y) std::copy_n(&f.heights[size_t(y0 + y) * f.width + x0], w, &out.heights[size_t(y) * w]);
    return out;
}

struct Texture {
    int width = 0, height = 0;
    std::vector<float> heights;
    std::vector<uint8_t> types;
};

class Exporter {
public:
    Exporter(const HeightSource& source, const GltfExportOptions& options) : source_(source), o_(options) {
        width_ = o_.region.width, height_ = o_.region.height;
        tiles_x_ = (width_ - 2) / o_.tile_size + 1;
        tiles_y_ = (height_ - 2) / o_.tile_size + 1;
        threads_ = o_.threads > 0 ? o_.threads : std::max(1u, std::thread::hardware_concurrency());
        tiles_.resize(size_t(tiles_x_) * tiles_y_);
        band_min_.assign(tiles_y_, INFINITY);
        band_max_.assign(tiles_y_, -INFINITY);
        if (o_.texture_size > 0) {
            const double aspect = double(height_) / width_;
            texture_.width = aspect <= 1.0 ? std::min(o_.texture_size, width_) : std::max(1, int(std::lround(std::min(o_.texture_size, height_) / aspect)));
            texture_.height = aspect <= 1.0 ? std::max(1, int(std::lround(texture_.width * aspect))) : std::min(o_.texture_size, height_);
            texture_.heights.assign(size_t(texture_.width) * texture_.height, 0.0f);
            texture_.types.assign(texture_.heights.size(), 255);
        }
    }

    Result<GltfExportStats> run(FileTransaction& transaction, const std::string& path) {
        if (Status s = parallelFor(tiles_y_, threads_, [this](int ty) { return meshBand(ty); }); !s) return s;
        const float lo = *std::min_element(band_min_.begin(), band_min_.end());
        const float hi = *std::max_element(band_max_.begin(), band_max_.end());
        int largest = 0;
        for (const MeshedTile& t : tiles_) largest = std::max({largest, t.quads_x, t.quads_y});
        PackingFrame frame = choosePackingFrame(o_.quantize, mpp_x_, mpp_y_, largest, lo, hi);
        frame.region_width = width_, frame.region_height = height_;
        frame.colors = o_.vertex_colors;

        GltfExportStats stats;
        stats.tiles_x = tiles_x_, stats.tiles_y = tiles_y_;
        stats.quantum_m = frame.quantum_m;
        stats.lods.resize(o_.lods);
        for (const MeshedTile& t : tiles_) {
            for (int k = 0; k < o_.lods; ++k) {
                stats.lods[k].vertices += t.lods[k].vertexCount();
                stats.lods[k].triangles += t.lods[k].triangleCount();
                stats.lods[k].max_geometric_error_m = std::max(stats.lods[k].max_geometric_error_m, t.lods[k].geometric_error_m);
            }
        }
        std::vector<PackedTile> packed(tiles_.size());
        parallelFor(static_cast<int>(tiles_.size()), threads_, [&](int i) {
            packed[i] = packTile(tiles_[i], frame);
            tiles_[i] = MeshedTile();  // the packed copy is all we need now
            return Status::ok();
        });
        for (const PackedTile& t : packed)
            for (const auto& lod : t.lods) stats.primitives += lod.size();

        std::string png;
        if (o_.texture_size > 0) {
            auto encoded = renderTexture(lo, hi);
            if (!encoded) return encoded.status().withContext(path);
            png = std::move(*encoded);
        }
        // One model holding every LOD (MSFT_lod), or one per LOD file.
        const bool lod_files = o_.lods > 1 && o_.lod_layout == LodLayout::Files;
        for (int lod = 0; lod < (lod_files ? o_.lods : 1); ++lod) {
            tinygltf::Model model;
            BinaryLayout layout;
            ModelInputs inputs{&o_, &frame, &packed, tiles_x_, tiles_y_, &png, lod_files ? lod : -1};
            buildModel(inputs, model, layout);
            const std::string file = lod_files ? gltfLodPath(path, lod) : path;
            size_t json_bytes = 0, file_bytes = 0;
            if (Status s = stageGltfFiles(transaction, file, model, layout, &json_bytes, &file_bytes); !s) return s;
            stats.binary_bytes += layout.total_bytes;
            stats.json_bytes += json_bytes;
            stats.file_bytes += file_bytes;
            stats.files.push_back(file);
        }
        return stats;
    }

private:
    // One row of tiles: heights with a 1-pixel apron for normals, types without.
    Status meshBand(int ty) {
        const int y0 = ty * o_.tile_size;
        const int quads_y = std::min(o_.tile_size, height_ - 1 - y0);
        const PixelWindow window{o_.region.x - 1, o_.region.y + y0 - 1, width_ + 2, quads_y + 3};
        auto band = source_(window, o_.level);
        if (!band) return band.status().withContext(windowText(window));
        if (band->width != window.width || band->height != window.height)
            return Status::error(windowText(window) + ": the source returned " + std::to_string(band->width) + "x" +
                                 std::to_string(band->height) + " samples");
        if (Status s = validateHeightfield(*band); !s) return s.withContext(windowText(window));
        std::vector<uint8_t> types;
        if (o_.types) {
            const PixelWindow tw{o_.region.x, o_.region.y + y0, width_, quads_y + 1};
            auto typed = o_.types(tw, o_.level);
            if (!typed) return typed.status().withContext("types " + windowText(tw));
            if (typed->size() != size_t(tw.width) * tw.height)
                return Status::error("types " + windowText(tw) + ": wrong number of samples");
            types = std::move(*typed);
        }
        recordBand(ty, *band, types, y0, quads_y);
        for (int tx = 0; tx < tiles_x_; ++tx) {
            MeshedTile& tile = tiles_[size_t(ty) * tiles_x_ + tx];
            tile.tx = tx, tile.ty = ty;
            tile.x0 = tx * o_.tile_size, tile.y0 = y0;
            tile.quads_x = std::min(o_.tile_size, width_ - 1 - tile.x0), tile.quads_y = quads_y;
            const Heightfield field = cropField(*band, tile.x0, 0, tile.quads_x + 3, quads_y + 3);
            for (int k = 0; k < o_.lods; ++k) tile.lods.push_back(meshHeightfield(field, lodOptions(k)));
            if (!types.empty()) {
                tile.types.resize(size_t(tile.quads_x + 1) * (quads_y + 1));
                for (int y = 0; y <= quads_y; ++y)
                    std::copy_n(&types[size_t(y) * width_ + tile.x0], tile.quads_x + 1, &tile.types[size_t(y) * (tile.quads_x + 1)]);
            }
        }
        return Status::ok();
    }

    MeshOptions lodOptions(int lod) const {
        MeshOptions m;
        m.border = 1;
        m.optimize_order = true;
        if (o_.lod_method == LodMethod::StitchedGrid) {
            m.step = lodStep(lod);
            m.full_res_border = true;
        } else {
            m.simplify_ratio = lodSimplifyRatio(lod);
        }
        return m;
    }

    // Height range and spacing of the band's own samples, and its share of the texture samples.
    void recordBand(int ty, const Heightfield& band, const std::vector<uint8_t>& types, int y0, int quads_y) {
        float lo = INFINITY, hi = -INFINITY;
        for (int y = 1; y <= quads_y + 1; ++y)
            for (int x = 1; x <= width_; ++x) lo = std::min(lo, band.at(x, y)), hi = std::max(hi, band.at(x, y));
        band_min_[ty] = lo, band_max_[ty] = hi;
        if (ty == 0) mpp_x_ = band.meters_per_pixel_x, mpp_y_ = band.meters_per_pixel_y;
        if (texture_.width == 0) return;
        // Texel centres sample the nearest region sample: texel j spans v in [j, j+1]/height and
        // vertex v = row / (height_ - 1).
        for (int j = 0; j < texture_.height; ++j) {
            const int r = std::clamp(int(std::lround((j + 0.5) / texture_.height * (height_ - 1))), 0, height_ - 1);
            const bool mine = (r >= y0 && r < y0 + quads_y) || (r == y0 + quads_y && ty == tiles_y_ - 1);
            if (!mine) continue;
            for (int i = 0; i < texture_.width; ++i) {
                const int c = std::clamp(int(std::lround((i + 0.5) / texture_.width * (width_ - 1))), 0, width_ - 1);
                texture_.heights[size_t(j) * texture_.width + i] = band.at(c + 1, r - y0 + 1);
                if (!types.empty()) texture_.types[size_t(j) * texture_.width + i] = types[size_t(r - y0) * width_ + c];
            }
        }
    }

    Result<std::string> renderTexture(float lo, float hi) const {
        std::vector<uint8_t> rgb(texture_.heights.size() * 3);
        const float range = std::max(hi - lo, 1e-6f);
        for (size_t p = 0; p < texture_.heights.size(); ++p) {
            const auto c = terrainColor((texture_.heights[p] - lo) / range, texture_.types[p]);
            std::copy(c.begin(), c.end(), &rgb[3 * p]);
        }
        return encodePngRgb(texture_.width, texture_.height, rgb);
    }

    static std::string windowText(const PixelWindow& w) {
        return "window (" + std::to_string(w.x) + ", " + std::to_string(w.y) + ", " + std::to_string(w.width) + "x" +
               std::to_string(w.height) + ")";
    }

    const HeightSource& source_;
    const GltfExportOptions& o_;
    int width_ = 0, height_ = 0, tiles_x_ = 0, tiles_y_ = 0, threads_ = 1;
    double mpp_x_ = 1.0, mpp_y_ = 1.0;
    std::vector<MeshedTile> tiles_;
    std::vector<float> band_min_, band_max_;
    Texture texture_;
};

}  // namespace

bool isGltfPath(const std::string& path) {
    return detail::hasExtension(path, ".glb") || detail::hasExtension(path, ".gltf");
}

std::string gltfLodPath(const std::string& path, int lod) {
    if (lod <= 0) return path;
    const std::string ext = detail::hasExtension(path, ".gltf") ? path.substr(path.size() - 5) : path.substr(path.size() - 4);
    return path.substr(0, path.size() - ext.size()) + "_lod" + std::to_string(lod) + ext;
}

Result<GltfExportStats> stageGltf(FileTransaction& transaction, const std::string& path, const HeightSource& source,
                                  const GltfExportOptions& options) {
    if (!isGltfPath(path)) return Status::error(path + ": the output must end in .glb or .gltf");
    if (Status s = checkOptions(options); !s) return s;
    if (!source) return Status::error("exportGltf: no height source");
    return Exporter(source, options).run(transaction, path);
}

Result<GltfExportStats> exportGltf(const std::string& path, const HeightSource& source, const GltfExportOptions& options) {
    FileTransaction transaction;
    auto stats = stageGltf(transaction, path, source, options);
    if (!stats) return stats;
    if (Status s = transaction.commit(); !s) return s;
    return stats;
}

}  // namespace terrasynth
