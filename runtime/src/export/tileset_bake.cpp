// bakeTiles: this shard's units -> skip the complete ones -> one window of samples per unit -> each
// tile's heightmap, masks and .glb (the .glb last: it marks the tile complete).
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <mutex>
#include <thread>

#include "export/export_internal.h"
#include "export/tileset_plan.h"
#include "terrasynth/file_transaction.h"
#include "terrasynth/gltf_export.h"

namespace terrasynth {

using namespace bake_detail;
namespace fs = std::filesystem;

BakeSource bakeSourceFrom(HeightSource heights, TypeSource types) {
    return [heights, types](const PixelWindow& window, int level, bool want_types) -> Result<BakeSamples> {
        BakeSamples out;
        auto h = heights(window, level);
        if (!h) return h.status();
        out.heights = std::move(*h);
        if (want_types) {
            if (!types) return Status::error("type masks asked for, but the source has no types");
            auto t = types(window, level);
            if (!t) return t.status();
            out.types = std::move(*t);
        }
        return out;
    };
}

namespace {

std::string windowText(const PixelWindow& w, int level) {
    return "window (" + std::to_string(w.x) + ", " + std::to_string(w.y) + ", " + std::to_string(w.width) + "x" +
           std::to_string(w.height) + ") at level " + std::to_string(level);
}

const char* heightmapExtension(HeightmapFormat f) {
    switch (f) {
        case HeightmapFormat::Png16: return ".png";
        case HeightmapFormat::Float32: return ".f32";
        case HeightmapFormat::GeoTiff: return ".tif";
        default: return "";
    }
}

Heightfield cropSamples(const Heightfield& f, int x0, int y0, int w, int h) {
    Heightfield out(w, h, f.meters_per_pixel_x);
    out.meters_per_pixel_y = f.meters_per_pixel_y;
    for (int y = 0; y < h; ++y) std::copy_n(&f.heights[size_t(y0 + y) * f.width + x0], w, &out.heights[size_t(y) * w]);
    return out;
}

std::vector<uint8_t> cropTypes(const std::vector<uint8_t>& types, int width, int x0, int y0, int w, int h) {
    std::vector<uint8_t> out(size_t(w) * h);
    for (int y = 0; y < h; ++y) std::copy_n(&types[size_t(y0 + y) * width + x0], w, &out[size_t(y) * w]);
    return out;
}

class ShardBaker {
public:
    ShardBaker(const std::string& folder, const BakeSource& source, const BakeOptions& options)
        : folder_(folder), source_(source), o_(options), tree_(options), units_(orderedUnits(tree_)) {
        shardRange(units_, o_.shard_index, o_.shard_count, &first_, &last_);
        for (size_t k = first_; k < last_; ++k) progress_.tiles_total += static_cast<int64_t>(unitTiles(tree_, units_[k]).size());
    }

    Result<BakeStats> run() {
        start_ = std::chrono::steady_clock::now();
        removeStaleTemporaries();
        const int threads = o_.threads > 0 ? o_.threads : std::max(1u, std::thread::hardware_concurrency());
        report();
        Status s = export_detail::parallelFor(static_cast<int>(last_ - first_), threads,
                                              [this](int k) { return bakeUnit(units_[first_ + size_t(k)]); });
        if (!s) return s;
        stats_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
        return stats_;
    }

private:
    std::string filePath(const std::string& relative) const { return folder_ + "/" + relative; }

    // Whether the tile's files on disk can be kept: each whole, matching the unit's record when there
    // is one (else a .glb must still be a sound container naming this tile). What was found goes
    // into `found` for the unit's new record.
    bool tileVerified(const TileKey& t, const RecordedFiles* record, RecordedFiles* found) const {
        for (const std::string& f : tileFiles(tree_, o_, t)) {
            const FileDigest* recorded = nullptr;
            if (record) {
                auto it = record->find(f);
                if (it == record->end()) return false;
                recorded = &it->second;
            }
            auto digest = verifyTileFile(folder_, f, t, recorded, nullptr);
            if (!digest) return false;
            (*found)[f] = *digest;
        }
        return true;
    }

    Status bakeUnit(const BakeUnit& unit) {
        std::vector<TileKey> todo;
        const std::vector<TileKey> tiles = unitTiles(tree_, unit);
        auto record = readUnitRecord(folder_, tree_, o_, unit);  // absent or unreadable: rewritten below
        RecordedFiles found;
        for (const TileKey& t : tiles)
            if (!tileVerified(t, record ? &record.value() : nullptr, &found)) todo.push_back(t);
        if (todo.empty()) {
            if (!record)
                if (Status s = writeUnitRecord(folder_, tree_, o_, unit, found); !s) return s;
            return finished(static_cast<int64_t>(tiles.size()), 0, 0);
        }

        const int level = BakeTree::sourceLevel(unit.lod);
        const PixelWindow window = unitWindow(tree_, unit);
        const bool want_types = o_.type_masks && unit.lod == 1;
        auto samples = source_(window, level, want_types);
        if (!samples) return samples.status().withContext(windowText(window, level));
        const Heightfield& field = samples->heights;
        if (field.width != window.width || field.height != window.height)
            return Status::error(windowText(window, level) + ": the source returned " + std::to_string(field.width) + "x" +
                                 std::to_string(field.height) + " samples");
        if (Status s = validateHeightfield(field); !s) return s.withContext(windowText(window, level));
        if (want_types && samples->types.size() != field.size())
            return Status::error(windowText(window, level) + ": the source returned the wrong number of types");

        int64_t bytes = 0;
        for (const TileKey& t : todo) {
            const SampleSpan span = tree_.samples(t);
            // Leaves read their samples plus a 1-sample apron out of the block's level-0 window.
            const int border = t.lod == 0 ? 1 : kApron;
            const int x0 = static_cast<int>(span.x0 - window.x) - border, y0 = static_cast<int>(span.y0 - window.y) - border;
            const Heightfield tile_field = cropSamples(field, x0, y0, span.quadsX() + 1 + 2 * border, span.quadsY() + 1 + 2 * border);
            const std::string dir = folder_ + "/" + tree_.tilePath(t, "");
            std::error_code ec;
            fs::create_directories(dir.substr(0, dir.find_last_of('/')), ec);
            if (ec) return Status::error(dir + ": cannot create the folder (" + ec.message() + ")");
            if (t.lod == 0) {
                if (Status s = writeLeafExtras(t, span, tile_field, border, samples->types, field.width, x0, y0); !s) return s;
            }
            auto record = writeTileGlb(filePath(tree_.tilePath(t, ".glb")), tree_, t, tile_field, border, o_.quantize);
            if (!record) return record.status();
            bytes += record->file_bytes;
        }
        // Written last: a unit with a record is done (its files read back from disk, so the record
        // says what is there).
        for (const TileKey& t : todo)
            for (const std::string& f : tileFiles(tree_, o_, t)) found.erase(f);
        if (Status s = writeUnitRecord(folder_, tree_, o_, unit, found); !s) return s;
        return finished(static_cast<int64_t>(tiles.size() - todo.size()), static_cast<int64_t>(todo.size()), bytes);
    }

    // Heightmap and splat masks of a leaf: its own T+1 samples, no apron.
    Status writeLeafExtras(const TileKey& t, const SampleSpan& span, const Heightfield& tile_field, int border,
                           const std::vector<uint8_t>& types, int types_width, int x0, int y0) {
        const int w = span.quadsX() + 1, h = span.quadsY() + 1;
        if (o_.heightmaps != HeightmapFormat::None) {
            const Heightfield own = cropSamples(tile_field, border, border, w, h);
            const double spacing = own.meters_per_pixel_x;
            const std::string path = filePath(tree_.tilePath(t, heightmapExtension(o_.heightmaps)));
            if (Status s = exportHeightmap(path, own, span.x0 * spacing, -span.y0 * spacing); !s) return s;
        }
        if (o_.type_masks) {
            const std::vector<uint8_t> own = cropTypes(types, types_width, x0 + border, y0 + border, w, h);
            auto written = writeTypeMasks(folder_ + "/" + tree_.tilePath(t, ".mask_"), w, h, own, o_.type_names);
            if (!written) return written.status();
        }
        return Status::ok();
    }

    Status finished(int64_t skipped, int64_t baked, int64_t bytes) {
        std::lock_guard<std::mutex> lock(mutex_);
        stats_.tiles_skipped += skipped;
        stats_.tiles_baked += baked;
        stats_.bytes_written += bytes;
        progress_.tiles_skipped += skipped;
        progress_.tiles_done += skipped + baked;
        reportLocked();
        return Status::ok();
    }

    void report() {
        std::lock_guard<std::mutex> lock(mutex_);
        reportLocked();
    }
    void reportLocked() {
        if (!o_.progress) return;
        progress_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
        o_.progress(progress_);
    }

    // A killed run leaves temporaries (and commit backups) beside the files it was writing. Only
    // those whose writer is gone are removed: a duplicate of this shard, or another shard, may be
    // writing its own right now (FileTransaction::isStaleTemporary).
    void removeStaleTemporaries() {
        std::error_code ec;
        for (const char* sub : {"tiles", "units"}) {
            const fs::path root = fs::path(folder_) / sub;
            if (!fs::is_directory(root, ec)) continue;
            for (auto it = fs::recursive_directory_iterator(root, ec); !ec && it != fs::recursive_directory_iterator();
                 it.increment(ec))
                if (FileTransaction::isStaleTemporary(it->path().filename().string()) && it->is_regular_file(ec))
                    fs::remove(it->path(), ec);
        }
    }

    const std::string folder_;
    const BakeSource& source_;
    const BakeOptions& o_;
    const BakeTree tree_;
    const std::vector<BakeUnit> units_;
    size_t first_ = 0, last_ = 0;
    std::mutex mutex_;
    BakeProgress progress_;
    BakeStats stats_;
    std::chrono::steady_clock::time_point start_;
};

}  // namespace

namespace bake_detail {

std::vector<std::string> tileFiles(const BakeTree& tree, const BakeOptions& o, const TileKey& t) {
    std::vector<std::string> files;
    if (t.lod == 0 && o.heightmaps != HeightmapFormat::None) {
        files.push_back(tree.tilePath(t, heightmapExtension(o.heightmaps)));
        if (o.heightmaps != HeightmapFormat::GeoTiff) files.push_back(tree.tilePath(t, ".json"));  // the sidecar
    }
    if (t.lod == 0 && o.type_masks)
        for (size_t k = 0; k < o.type_names.size(); ++k) files.push_back(typeMaskPath(tree.tilePath(t, ".mask_"), o.type_names, k));
    files.push_back(tree.tilePath(t, ".glb"));
    return files;
}

bool tileFilesComplete(const std::string& folder, const std::vector<std::string>& files) {
    for (const std::string& f : files) {
        const std::string path = folder + "/" + f;
        const bool glb = f.size() > 4 && f.compare(f.size() - 4, 4, ".glb") == 0;
        if (glb ? !glbComplete(path) : !fs::exists(path)) return false;
    }
    return true;
}

}  // namespace bake_detail

Result<BakeStats> bakeTiles(const std::string& folder, const BakeSource& source, const BakeOptions& options) {
    if (Status s = checkBakeOptions(options); !s) return s;
    if (!source) return Status::error("bakeTiles: no source");
    return ShardBaker(folder, source, options).run();
}

}  // namespace terrasynth
