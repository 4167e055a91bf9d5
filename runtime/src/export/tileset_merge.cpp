// mergeTileset: the plan's tiles -> refuse if any is missing -> every file verified against its unit's
// record (size, digest, the .glb's container) and each tile's record from its verified .glb ->
// accumulated geometric errors and bounding boxes, children first -> tileset.json, explicit or implicit.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <thread>
#include <unordered_map>

#include "export/export_internal.h"
#include "export/tileset_implicit.h"
#include "terrasynth/heightfield_io.h"

namespace terrasynth {

using namespace bake_detail;
namespace fs = std::filesystem;

namespace {

struct KeyHash {
    size_t operator()(const TileKey& t) const {
        return std::hash<int64_t>()(t.i * 1000003 + t.j) ^ (static_cast<size_t>(t.lod) << 56);
    }
};

// 3D Tiles box: centre, then the x, y and z half-axes (world frame, z up).
nlohmann::json boxJson(const double b[6]) {
    const double c[3] = {(b[0] + b[3]) / 2, (b[1] + b[4]) / 2, (b[2] + b[5]) / 2};
    double h[3];
    for (int k = 0; k < 3; ++k) h[k] = std::max((b[3 + k] - b[k]) / 2, 1e-3);
    return {{"box", {c[0], c[1], c[2], h[0], 0.0, 0.0, 0.0, h[1], 0.0, 0.0, 0.0, h[2]}}};
}

void unite(double into[6], const double b[6]) {
    for (int k = 0; k < 3; ++k) into[k] = std::min(into[k], b[k]), into[3 + k] = std::max(into[3 + k], b[3 + k]);
}

struct MergedTile {
    TileRecord record;
    double error_m = 0.0;  // own error plus the largest of the children's
    double box[6];         // own content and every descendant's
    std::vector<size_t> children;
};

class Merger {
public:
    Merger(const std::string& folder, BakeOptions plan) : folder_(folder), plan_(std::move(plan)), tree_(plan_) {}

    // `refused`: the files that failed verification, when the merge is refused for them.
    Result<MergeStats> run(std::vector<std::string>* refused) {
        const std::vector<TileKey> keys = tree_.allTiles();
        tiles_.resize(keys.size());
        if (Status s = verifyTiles(keys, refused); !s) return s;
        accumulate(keys);

        MergeStats stats;
        stats.tiles = static_cast<int64_t>(keys.size());
        stats.depth = tree_.depth();
        for (const MergedTile& t : tiles_) stats.content_bytes += t.record.file_bytes;
        stats.implicit = plan_.layout == TilesetLayout::Implicit ||
                         (plan_.layout == TilesetLayout::Auto && tree_.depth() >= kImplicitFromDepth);
        nlohmann::json tileset;
        tileset["asset"] = {{"version", "1.1"}, {"generator", "terrasynth"}};
        tileset["extras"] = {{"terrasynth", {{"region", {plan_.region.x, plan_.region.y, plan_.region.width, plan_.region.height}},
                                             {"tile_size", plan_.tile_size},
                                             {"levels", plan_.levels},
                                             {"meters_per_pixel", plan_.meters_per_pixel},
                                             {"frame", "x east, y north, z up, metres; level-0 sample (0,0) at the origin"}}}};
        if (stats.implicit) {
            auto root = implicitRoot(&stats.root_geometric_error_m);
            if (!root) return root.status();
            tileset["root"] = std::move(*root);
        } else {
            tileset["root"] = explicitRoot(&stats.root_geometric_error_m);
        }
        tileset["geometricError"] = 2.0 * stats.root_geometric_error_m;
        if (Status s = writeFileAtomically(folder_ + "/tileset.json", tileset.dump() + "\n"); !s) return s;
        return stats;
    }

private:
    // Every file of every tile against its unit's record (size and digest) and every .glb's
    // container, each file read once; the tiles' records come from the verified bytes.
    Status verifyTiles(const std::vector<TileKey>& keys, std::vector<std::string>* refused) {
        std::map<std::string, RecordedFiles> records;  // by unit record path
        for (const TileKey& t : keys) {
            const BakeUnit unit = unitOf(t);
            if (records.count(unitRecordPath(unit))) continue;
            auto record = readUnitRecord(folder_, tree_, plan_, unit);
            if (!record) return refuse({unitRecordPath(unit)}, {record.message()}, refused);
            records[unitRecordPath(unit)] = std::move(record.value());
        }
        std::mutex mutex;
        std::vector<std::pair<std::string, std::string>> problems;  // file, message
        const int threads = std::max(1u, std::thread::hardware_concurrency());
        (void)export_detail::parallelFor(static_cast<int>(keys.size()), threads, [&](int k) -> Status {
            const RecordedFiles& record = records.at(unitRecordPath(unitOf(keys[k])));
            for (const std::string& f : tileFiles(tree_, plan_, keys[k])) {
                auto it = record.find(f);
                auto verified = verifyTileFile(folder_, f, keys[k], it == record.end() ? nullptr : &it->second,
                                               &tiles_[k].record);
                if (!verified) {
                    std::lock_guard<std::mutex> lock(mutex);
                    problems.push_back({f, verified.message()});
                }
            }
            return Status::ok();
        });
        if (problems.empty()) return Status::ok();
        std::sort(problems.begin(), problems.end());
        std::vector<std::string> files, messages;
        for (auto& [file, message] : problems) files.push_back(file), messages.push_back(message);
        return refuse(files, messages, refused);
    }

    Status refuse(const std::vector<std::string>& files, const std::vector<std::string>& messages,
                  std::vector<std::string>* refused) const {
        if (refused) *refused = files;
        std::string list;
        for (size_t k = 0; k < messages.size() && k < 5; ++k) list += (k ? "; " : "") + messages[k];
        if (messages.size() > 5) list += "; ... (" + std::to_string(messages.size() - 5) + " more)";
        return Status::error(folder_ + ": " + std::to_string(files.size()) + " file" + (files.size() > 1 ? "s" : "") +
                             " failed verification, nothing merged: " + list + "; re-run the shards that own them");
    }

    // Children before parents (the reverse of the pre-order): errors add up and boxes grow upwards.
    void accumulate(const std::vector<TileKey>& keys) {
        std::unordered_map<TileKey, size_t, KeyHash> index;
        for (size_t k = 0; k < keys.size(); ++k) index[keys[k]] = k;
        for (size_t k = keys.size(); k-- > 0;) {
            MergedTile& t = tiles_[k];
            std::copy(t.record.bounds, t.record.bounds + 6, t.box);
            double worst_child = 0.0;
            if (keys[k].lod > 0) {
                for (int b = 0; b < 2; ++b)
                    for (int a = 0; a < 2; ++a) {
                        auto it = index.find({keys[k].lod - 1, 2 * keys[k].i + a, 2 * keys[k].j + b});
                        if (it == index.end()) continue;
                        t.children.push_back(it->second);
                        worst_child = std::max(worst_child, tiles_[it->second].error_m);
                        unite(t.box, tiles_[it->second].box);
                    }
            }
            t.error_m = t.record.own_error_m + worst_child;
            if (keys[k].lod == tree_.levels() - 1) tops_.push_back(k);
        }
        std::reverse(tops_.begin(), tops_.end());
    }

    nlohmann::json explicitTile(size_t k) const {
        const MergedTile& t = tiles_[k];
        nlohmann::json j;
        j["boundingVolume"] = boxJson(t.box);
        j["geometricError"] = t.error_m;
        j["content"] = {{"uri", tree_.tilePath(t.record.key, ".glb")}};
        if (!t.children.empty()) {
            nlohmann::json children = nlohmann::json::array();
            for (size_t c : t.children) children.push_back(explicitTile(c));
            j["children"] = std::move(children);
        }
        return j;
    }

    nlohmann::json explicitRoot(double* root_error) const {
        if (tops_.size() == 1) {
            nlohmann::json root = explicitTile(tops_.front());
            root["refine"] = "REPLACE";
            *root_error = tiles_[tops_.front()].error_m;
            return root;
        }
        // Several coarsest tiles: an empty root holds them.
        double box[6] = {INFINITY, INFINITY, INFINITY, -INFINITY, -INFINITY, -INFINITY}, worst = 0.0;
        nlohmann::json children = nlohmann::json::array();
        for (size_t k : tops_) {
            unite(box, tiles_[k].box);
            worst = std::max(worst, tiles_[k].error_m);
            children.push_back(explicitTile(k));
        }
        *root_error = 2.0 * worst;
        return {{"boundingVolume", boxJson(box)}, {"geometricError", *root_error}, {"refine", "REPLACE"},
                {"children", std::move(children)}};
    }

    // Implicit tiling fixes every tile's error at root / 2^depth: the smallest root error that keeps
    // each tile's implied error at or above its measured one. Boxes split the root box in x and y.
    Result<nlohmann::json> implicitRoot(double* root_error) const {
        double box[6] = {0, 0, INFINITY, 0, 0, -INFINITY}, worst = 0.0;
        tree_.rootExtent(&box[0], &box[1], &box[3], &box[4]);
        for (const MergedTile& t : tiles_) {
            box[2] = std::min(box[2], t.box[2]), box[5] = std::max(box[5], t.box[5]);
            worst = std::max(worst, std::ldexp(t.error_m, tree_.implicitOf(t.record.key).depth));
        }
        *root_error = worst;
        const int subtree_levels = subtreeLevels(tree_.depth());
        if (Status s = writeSubtrees(folder_, tree_, subtree_levels); !s) return s;
        nlohmann::json root;
        root["boundingVolume"] = boxJson(box);
        root["geometricError"] = worst;
        root["refine"] = "REPLACE";
        root["content"] = {{"uri", "tiles/{level}/{x}/{y}.glb"}};
        root["implicitTiling"] = {{"subdivisionScheme", "QUADTREE"},
                                  {"subtreeLevels", subtree_levels},
                                  {"availableLevels", tree_.depth()},
                                  {"subtrees", {{"uri", std::string(kSubtreeTemplate)}}}};
        return root;
    }

    const std::string folder_;
    const BakeOptions plan_;
    const BakeTree tree_;
    std::vector<MergedTile> tiles_;
    std::vector<size_t> tops_;  // the coarsest tiles, in tree order
};

}  // namespace

Result<std::vector<std::string>> findMissingTiles(const std::string& folder) {
    auto plan = readPlan(folder);
    if (!plan) return plan.status();
    const BakeTree tree(*plan);
    std::vector<std::string> missing;
    for (const TileKey& t : tree.allTiles()) {
        for (const std::string& f : tileFiles(tree, *plan, t))
            if (!tileFilesComplete(folder, {f})) missing.push_back(f);
        // A unit's record comes with its first tile (the coarsest).
        const BakeUnit unit = unitOf(t);
        const std::string record = unitRecordPath(unit);
        if (unitTiles(tree, unit).front() == t && !fs::exists(folder + "/" + record)) missing.push_back(record);
    }
    return missing;
}

Result<MergeStats> mergeTileset(const std::string& folder, std::vector<std::string>* refused) {
    if (refused) refused->clear();
    auto missing = findMissingTiles(folder);
    if (!missing) return missing.status();
    if (!missing->empty()) {
        if (refused) *refused = *missing;
        std::string list;
        for (size_t k = 0; k < missing->size() && k < 10; ++k) list += (k ? ", " : "") + (*missing)[k];
        if (missing->size() > 10) list += ", ... (" + std::to_string(missing->size() - 10) + " more)";
        return Status::error(folder + ": " + std::to_string(missing->size()) + " tile file" + (missing->size() > 1 ? "s" : "") +
                             " missing or incomplete: " + list + "; re-run the shards that own them");
    }
    auto plan = readPlan(folder);
    if (!plan) return plan.status();
    return Merger(folder, *plan).run(refused);
}

}  // namespace terrasynth
