// Checking bake options, counting tiles, and the plan file (bake.json) that ties the shards of one
// bake together: every shard writes it or checks that it agrees, and the merge reads the tree from it.
#include <filesystem>
#include <nlohmann/json.hpp>

#include "export/tileset_plan.h"
#include "terrasynth/heightfield_io.h"
#include "terrasynth/limits.h"

namespace terrasynth {

using namespace bake_detail;
namespace fs = std::filesystem;

namespace {

const char* layoutName(TilesetLayout l) {
    return l == TilesetLayout::Explicit ? "explicit" : l == TilesetLayout::Implicit ? "implicit" : "auto";
}
const char* heightmapName(HeightmapFormat f) {
    switch (f) {
        case HeightmapFormat::Png16: return "png";
        case HeightmapFormat::Float32: return "f32";
        case HeightmapFormat::GeoTiff: return "tif";
        default: return "none";
    }
}

nlohmann::json planJson(const BakeOptions& o) {
    nlohmann::json j;
    j["format"] = "terrasynth-bake";
    j["version"] = 1;
    j["region"] = {o.region.x, o.region.y, o.region.width, o.region.height};
    j["tile_size"] = o.tile_size;
    j["levels"] = o.levels;
    j["meters_per_pixel"] = o.meters_per_pixel;
    j["quantize"] = o.quantize;
    j["tileset"] = layoutName(o.layout);
    j["heightmaps"] = heightmapName(o.heightmaps);
    j["type_masks"] = o.type_masks ? nlohmann::json(o.type_names) : nlohmann::json::array();
    j["source"] = o.source_id;
    return j;
}

}  // namespace

Status checkBakeOptions(const BakeOptions& o) {
    if (o.region.width < 2 || o.region.height < 2)
        return Status::error("region: needs at least 2x2 samples (1 quad), got " + std::to_string(o.region.width) + "x" +
                             std::to_string(o.region.height));
    // What synthesis serves: every window of every LOD, with its apron, inside the grid (the
    // project origin's bound). Compared before adding, so x + width cannot overflow.
    const int64_t limit = limits::kMaxProjectOrigin;
    if (o.region.x < -limit || o.region.y < -limit || o.region.x > limit - o.region.width ||
        o.region.y > limit - o.region.height)
        return Status::error("region: must lie within +-2^28 (" + std::to_string(limit) +
                             ") samples of the origin, the grid synthesis serves (docs/limits.md)");
    // The cost, refused at once rather than found by running out of memory: samples and tiles.
    const uint64_t samples = static_cast<uint64_t>(o.region.width) * static_cast<uint64_t>(o.region.height);
    if (samples > limits::kMaxBakeSamples)
        return Status::error("region: " + std::to_string(o.region.width) + "x" + std::to_string(o.region.height) + " = " +
                             std::to_string(samples) + " samples, at most " + std::to_string(limits::kMaxBakeSamples) +
                             " in one bake (docs/limits.md); bake it as several regions");
    if (o.tile_size < 2 || o.tile_size > 4096)
        return Status::error("tile size: must be 2..4096 quads, got " + std::to_string(o.tile_size));
    if (o.levels < 1 || o.levels > 16) return Status::error("levels: must be 1..16, got " + std::to_string(o.levels));
    if (o.levels >= 2 && o.levels - 2 > o.max_source_level)
        return Status::error("levels: " + std::to_string(o.levels) + " LODs mesh pyramid level " +
                             std::to_string(o.levels - 2) + ", but the terrain has levels 0.." +
                             std::to_string(o.max_source_level));
    if (!(o.meters_per_pixel > 0.0)) return Status::error("meters per pixel: must be positive");
    if (o.shard_count < 1)
        return Status::error("shard: " + std::to_string(o.shard_index) + "/" + std::to_string(o.shard_count) +
                             ": the shard count must be at least 1");
    if (o.shard_index < 0 || o.shard_index >= o.shard_count)
        return Status::error("shard: " + std::to_string(o.shard_index) + "/" + std::to_string(o.shard_count) +
                             ": the index must be 0.." + std::to_string(o.shard_count - 1));
    if (o.type_masks && o.type_names.empty()) return Status::error("masks: the terrain has no type names");
    const BakeTree tree(o);
    if (tree.depth() > 30) return Status::error("region: too large for " + std::to_string(o.levels) + " levels of " +
                                                std::to_string(o.tile_size) + "-quad tiles (tree deeper than 30)");
    int64_t tiles = 0;
    for (int lod = 0; lod < tree.levels(); ++lod) tiles += tree.range(lod).countI() * tree.range(lod).countJ();
    if (tiles > limits::kMaxBakeTiles)
        return Status::error("region: " + std::to_string(o.region.width) + "x" + std::to_string(o.region.height) +
                             " samples in " + std::to_string(o.tile_size) + "-quad tiles and " + std::to_string(o.levels) +
                             " levels make " + std::to_string(tiles) + " tiles, at most " +
                             std::to_string(limits::kMaxBakeTiles) + " (docs/limits.md); use larger tiles");
    return Status::ok();
}

BakeCounts countBakeTiles(const BakeOptions& options) {
    const BakeTree tree(options);
    BakeCounts c;
    c.depth = tree.depth();
    for (int lod = 0; lod < tree.levels(); ++lod) c.tiles += tree.range(lod).countI() * tree.range(lod).countJ();
    const std::vector<BakeUnit> units = orderedUnits(tree);
    size_t first = 0, last = 0;
    shardRange(units, options.shard_index, options.shard_count, &first, &last);
    c.units = static_cast<int64_t>(units.size());
    c.shard_units = static_cast<int64_t>(last - first);
    for (size_t k = first; k < last; ++k) c.shard_tiles += static_cast<int64_t>(unitTiles(tree, units[k]).size());
    return c;
}

namespace bake_detail {

std::string planText(const BakeOptions& options) { return planJson(options).dump(2) + "\n"; }

Result<BakeOptions> readPlan(const std::string& folder) {
    const std::string path = folder + "/" + kPlanFile;
    auto bytes = readFileBytes(path);
    if (!bytes) return Status::error(path + ": no bake plan here (is this a bake output folder?)");
    const nlohmann::json j = nlohmann::json::parse(*bytes, nullptr, /*allow_exceptions=*/false);
    if (j.is_discarded() || !j.is_object() || j.value("format", "") != "terrasynth-bake")
        return Status::error(path + ": not a terrasynth bake plan");
    if (j.value("version", 0) != 1) return Status::error(path + ": unsupported plan version");
    BakeOptions o;
    try {
        const auto& r = j.at("region");
        o.region = {r.at(0).get<int64_t>(), r.at(1).get<int64_t>(), r.at(2).get<int>(), r.at(3).get<int>()};
        o.tile_size = j.at("tile_size").get<int>();
        o.levels = j.at("levels").get<int>();
        o.max_source_level = 64;
        o.meters_per_pixel = j.at("meters_per_pixel").get<double>();
        o.quantize = j.at("quantize").get<bool>();
        const std::string layout = j.at("tileset").get<std::string>();
        o.layout = layout == "explicit" ? TilesetLayout::Explicit : layout == "implicit" ? TilesetLayout::Implicit : TilesetLayout::Auto;
        const std::string heightmaps = j.at("heightmaps").get<std::string>();
        o.heightmaps = heightmaps == "png" ? HeightmapFormat::Png16 : heightmaps == "f32" ? HeightmapFormat::Float32
                     : heightmaps == "tif" ? HeightmapFormat::GeoTiff : HeightmapFormat::None;
        o.type_names = j.at("type_masks").get<std::vector<std::string>>();
        o.type_masks = !o.type_names.empty();
        o.source_id = j.at("source").get<std::string>();
    } catch (const nlohmann::json::exception& e) {
        return Status::error(path + ": malformed plan (" + e.what() + ")");
    }
    if (Status s = checkBakeOptions(o); !s) return s.withContext(path);
    return o;
}

}  // namespace bake_detail

namespace {

// What differs between two plans, for the refusal message.
std::string planDifference(const std::string& existing, const BakeOptions& wanted) {
    const nlohmann::json a = nlohmann::json::parse(existing, nullptr, false), b = planJson(wanted);
    if (a.is_discarded() || !a.is_object()) return "it is not a bake plan";
    std::string out;
    for (const auto& [key, value] : b.items()) {
        if (a.contains(key) && a.at(key) == value) continue;
        if (!out.empty()) out += ", ";
        out += key + " " + (a.contains(key) ? a.at(key).dump() : "(none)") + " there, " + value.dump() + " here";
    }
    return out.empty() ? "its text differs" : out;
}

}  // namespace

Status prepareBakeFolder(const std::string& folder, const BakeOptions& options) {
    if (folder.empty()) return Status::error("output: no folder given");
    std::error_code ec;
    // The outermost folder this call creates, removed again if anything fails.
    fs::path created;
    for (fs::path p = fs::absolute(folder, ec); !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
        created = p;
        if (p == p.parent_path()) break;
    }
    fs::create_directories(folder, ec);
    if (ec || !fs::is_directory(folder)) {
        if (!created.empty() && fs::is_directory(created)) fs::remove_all(created, ec);
        return Status::error(folder + ": cannot create the output folder (" + (ec ? ec.message() : "not a folder") + ")");
    }
    const std::string plan_path = folder + "/" + kPlanFile;
    const std::string wanted = planText(options);
    if (fs::exists(plan_path)) {
        auto existing = readFileBytes(plan_path);
        if (!existing) return existing.status();
        if (*existing != wanted)
            return Status::error(plan_path + ": this folder holds another bake (" + planDifference(*existing, options) +
                                 "); use a new folder or delete it");
        return Status::ok();
    }
    if (Status s = writeFileAtomically(plan_path, wanted); !s) {
        if (!created.empty()) fs::remove_all(created, ec);
        return Status::error(folder + ": the output folder is not writable (" + s.message() + ")");
    }
    return Status::ok();
}

}  // namespace terrasynth
