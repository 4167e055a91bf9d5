// The tileset bake on a real DEM (terrasynth/tileset_bake.h and its private plan): the tree and the
// shard assignment, bytes independent of shards and threads, re-runs, errors and boxes of the
// merged tileset, implicit availability.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "export/tileset_implicit.h"
#include "export/tileset_plan.h"
#include "terrasynth/file_transaction.h"
#include "terrasynth/gltf_export.h"
#include "terrasynth/tileset_bake.h"
#include "temporary_names.h"
#include "test_support.h"

using namespace terrasynth;
using namespace terrasynth::bake_detail;
namespace fs = std::filesystem;

namespace {

// Level k of a real DEM: the mean of each 2^k x 2^k block of level-0 samples, the DEM mirrored
// beyond its edges (so the world is unbounded and windows agree bit for bit).
BakeSource demSource() {
    static const Heightfield dem = test::loadExemplarField("orom_alaska");
    return [](const PixelWindow& w, int level, bool want_types) -> Result<BakeSamples> {
        const int64_t block = int64_t(1) << level;
        auto mirror = [](int64_t v, int n) {
            const int64_t period = 2 * int64_t(n);
            int64_t m = ((v % period) + period) % period;
            return static_cast<int>(m < n ? m : period - 1 - m);
        };
        BakeSamples out;
        out.heights = Heightfield(w.width, w.height, dem.meters_per_pixel_x * block);
        for (int y = 0; y < w.height; ++y)
            for (int x = 0; x < w.width; ++x) {
                double sum = 0.0;
                for (int64_t by = 0; by < block; ++by)
                    for (int64_t bx = 0; bx < block; ++bx)
                        sum += dem.at(mirror((w.x + x) * block + bx, dem.width), mirror((w.y + y) * block + by, dem.height));
                out.heights.at(x, y) = static_cast<float>(sum / double(block * block));
            }
        if (want_types)
            for (float h : out.heights.heights) out.types.push_back(h > 2000.0f ? 1 : 0);
        return out;
    };
}

BakeOptions smallBake() {
    BakeOptions o;
    o.region = {-37, 21, 301, 230};  // not tile-aligned: clipped tiles on every side
    o.tile_size = 32;
    o.levels = 4;
    o.max_source_level = 5;
    o.meters_per_pixel = 92.6;
    o.source_id = "alaska";
    o.threads = 1;
    return o;
}


std::map<std::string, std::string> folderContents(const std::string& dir) {
    std::map<std::string, std::string> out;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        if (e.is_regular_file()) out[fs::relative(e.path(), dir).string()] = test::readFile(e.path().string());
    return out;
}

// Implicit tiles available at depths [d0, d1).
int availableTiles(const BakeTree& tree, int d0, int d1) {
    int n = 0;
    for (int d = d0; d < d1; ++d)
        for (int64_t x = 0; x < (int64_t(1) << d); ++x)
            for (int64_t y = 0; y < (int64_t(1) << d); ++y) n += implicitTileAvailable(tree, {d, x, y});
    return n;
}

void bakeAll(const std::string& dir, BakeOptions o, int shards) {
    o.shard_count = shards;
    for (int s = 0; s < shards; ++s) {
        o.shard_index = s;
        ASSERT_TRUE(prepareBakeFolder(dir, o));
        auto stats = bakeTiles(dir, demSource(), o);
        ASSERT_TRUE(stats) << stats.message();
    }
    auto merged = mergeTileset(dir);
    ASSERT_TRUE(merged) << merged.message();
}

}  // namespace

TEST(TilesetPlan, ShardsCoverEveryTileOnceInContiguousBalancedRuns) {
    const BakeOptions o = smallBake();
    ASSERT_TRUE(checkBakeOptions(o));
    const BakeTree tree(o);
    const std::vector<TileKey> tiles = tree.allTiles();
    // Pre-order: every tile's parent comes before it.
    std::map<std::tuple<int, int64_t, int64_t>, size_t> position;
    for (size_t k = 0; k < tiles.size(); ++k) position[{tiles[k].lod, tiles[k].i, tiles[k].j}] = k;
    for (size_t k = 0; k < tiles.size(); ++k) {
        if (tiles[k].lod == o.levels - 1) continue;
        auto parent = position.find({tiles[k].lod + 1, floorDiv(tiles[k].i, 2), floorDiv(tiles[k].j, 2)});
        ASSERT_NE(parent, position.end());
        EXPECT_LT(parent->second, k);
    }
    const std::vector<BakeUnit> units = orderedUnits(tree);
    double total = 0.0, largest = 0.0;
    for (const BakeUnit& u : units) total += u.weight, largest = std::max(largest, u.weight);
    for (int shards : {1, 2, 3, 7}) {
        std::multiset<std::tuple<int, int64_t, int64_t>> seen;
        size_t expected_first = 0;
        for (int s = 0; s < shards; ++s) {
            size_t first, last;
            shardRange(units, s, shards, &first, &last);
            if (first == last) continue;
            EXPECT_EQ(first, expected_first) << shards << " shards";
            expected_first = last;
            double weight = 0.0;
            for (size_t k = first; k < last; ++k) {
                weight += units[k].weight;
                for (const TileKey& t : unitTiles(tree, units[k])) seen.insert({t.lod, t.i, t.j});
            }
            EXPECT_LE(std::fabs(weight - total / shards), largest) << "shard " << s << "/" << shards;
            // Coarse levels are spread: with several shards, every shard gets coarse work too.
            BakeOptions mine = o;
            mine.shard_index = s, mine.shard_count = shards;
            EXPECT_GT(countBakeTiles(mine).shard_tiles, 0);
        }
        EXPECT_EQ(expected_first, units.size());
        EXPECT_EQ(seen.size(), tiles.size());
        const std::set<std::tuple<int, int64_t, int64_t>> distinct(seen.begin(), seen.end());
        EXPECT_EQ(distinct.size(), tiles.size());
    }
    // Implicit coordinates round-trip, and availability says exactly which tiles exist.
    for (const TileKey& t : tiles) EXPECT_TRUE(tree.tileAt(tree.implicitOf(t)) == t);
    EXPECT_EQ(availableTiles(tree, tree.emptyLevels(), tree.depth()), static_cast<int>(tiles.size()));
    EXPECT_GT(availableTiles(tree, 0, tree.emptyLevels()), 0);
}

TEST(TilesetBake, SameBytesWhateverTheShardAndThreadCounts) {
    const std::string a = test::scratchDir("tileset_one_shard"), b = test::scratchDir("tileset_three_shards");
    BakeOptions o = smallBake();
    o.quantize = true;
    o.heightmaps = HeightmapFormat::GeoTiff;
    o.type_masks = true;
    o.type_names = {"low", "high"};
    bakeAll(a, o, 1);
    o.threads = 2;
    bakeAll(b, o, 3);
    const auto ca = folderContents(a), cb = folderContents(b);
    ASSERT_EQ(ca.size(), cb.size());
    for (const auto& [name, bytes] : ca) {
        ASSERT_TRUE(cb.count(name)) << name;
        EXPECT_TRUE(cb.at(name) == bytes) << name << " differs";
    }
    // Every leaf has its GeoTIFF heightmap and one mask per type beside its .glb.
    int leaves = 0;
    for (const auto& entry : ca) {
        const std::string& name = entry.first;
        if (name.size() < 4 || name.substr(name.size() - 4) != ".tif") continue;
        ++leaves;
        const std::string stem = name.substr(0, name.size() - 4);
        EXPECT_TRUE(ca.count(stem + ".glb") && ca.count(stem + ".mask_low.png") && ca.count(stem + ".mask_high.png")) << stem;
    }
    EXPECT_EQ(leaves, static_cast<int>(BakeTree(o).range(0).countI() * BakeTree(o).range(0).countJ()));
}

TEST(TilesetBake, MergedTreeHasGrowingErrorsNestedBoxesAndEveryTile) {
    const std::string dir = test::scratchDir("tileset_tree");
    BakeOptions o = smallBake();
    o.layout = TilesetLayout::Explicit;
    bakeAll(dir, o, 1);
    const nlohmann::json tileset = nlohmann::json::parse(test::readFile(dir + "/tileset.json"));
    EXPECT_EQ(tileset["asset"]["version"], "1.1");
    int contents = 0, leaves = 0;
    auto extent = [](const nlohmann::json& t, double e[6]) {
        const auto& b = t["boundingVolume"]["box"];
        for (int k = 0; k < 3; ++k) {
            const double half = b[3 + 4 * k].get<double>();
            e[k] = b[k].get<double>() - half, e[3 + k] = b[k].get<double>() + half;
        }
    };
    std::function<void(const nlohmann::json&)> walk = [&](const nlohmann::json& t) {
        contents += t.contains("content");
        if (!t.contains("children")) {
            ++leaves;
            EXPECT_EQ(t["geometricError"].get<double>(), 0.0);  // full resolution
            return;
        }
        double parent[6];
        extent(t, parent);
        for (const auto& c : t["children"]) {
            EXPECT_LT(c["geometricError"].get<double>(), t["geometricError"].get<double>());
            double child[6];
            extent(c, child);
            for (int k = 0; k < 3; ++k) {
                EXPECT_GE(child[k], parent[k] - 1e-6);
                EXPECT_LE(child[3 + k], parent[3 + k] + 1e-6);
            }
            walk(c);
        }
    };
    walk(tileset["root"]);
    EXPECT_EQ(contents, countBakeTiles(o).tiles);
    EXPECT_EQ(leaves, static_cast<int>(BakeTree(o).range(0).countI() * BakeTree(o).range(0).countJ()));
}

TEST(TilesetBake, RerunBakesOnlyMissingTilesAndClearsItsOwnTemporaries) {
    const std::string dir = test::scratchDir("tileset_rerun");
    BakeOptions o = smallBake();
    o.shard_count = 2;
    o.shard_index = 0;
    ASSERT_TRUE(prepareBakeFolder(dir, o));
    auto first = bakeTiles(dir, demSource(), o);
    ASSERT_TRUE(first) << first.message();
    const BakeTree tree(o);
    const std::vector<BakeUnit> units = orderedUnits(tree);
    size_t begin, end;
    shardRange(units, 0, 2, &begin, &end);
    const TileKey mine = unitTiles(tree, units[begin]).back();
    const TileKey theirs = unitTiles(tree, units[end]).back();
    const std::string mine_glb = dir + "/" + tree.tilePath(mine, ".glb");
    ASSERT_TRUE(fs::remove(mine_glb));
    // Temporaries are named "<file>.tmp.<host>.<pid>.<n>" (FileTransaction): a writer that died
    // (a child reaped at once) left half a tile, a live one (this process) is still writing.
    const pid_t dead = ::fork();
    if (dead == 0) ::_exit(0);
    ASSERT_GT(dead, 0);
    ASSERT_EQ(::waitpid(dead, nullptr, 0), dead);
    const std::string mine_tmp = test::temporaryOf(mine_glb, dead);
    const std::string theirs_tmp = test::temporaryOf(dir + "/" + tree.tilePath(theirs, ".glb"), ::getpid());
    ASSERT_TRUE(FileTransaction::isStaleTemporary(fs::path(mine_tmp).filename().string()));
    std::ofstream(mine_tmp) << "half a tile";
    fs::create_directories(fs::path(theirs_tmp).parent_path());
    std::ofstream(theirs_tmp) << "another shard, still writing";
    auto second = bakeTiles(dir, demSource(), o);
    ASSERT_TRUE(second) << second.message();
    EXPECT_EQ(second->tiles_baked, 1);
    EXPECT_EQ(second->tiles_skipped, first->tiles_baked - 1);
    EXPECT_TRUE(fs::exists(mine_glb));
    EXPECT_FALSE(fs::exists(mine_tmp));
    EXPECT_TRUE(fs::exists(theirs_tmp));
    // The other shard's tiles are missing, and the merge names them.
    auto missing = findMissingTiles(dir);
    ASSERT_TRUE(missing);
    EXPECT_FALSE(missing->empty());
    auto merged = mergeTileset(dir);
    EXPECT_FALSE(merged);
    EXPECT_NE(merged.message().find(tree.tilePath(theirs, ".glb")), std::string::npos) << merged.message();
    EXPECT_FALSE(fs::exists(dir + "/tileset.json"));
}

TEST(TilesetBake, PlansOfAnotherBakeAndBadOptionsAreRefused) {
    const std::string dir = test::scratchDir("tileset_refuse");
    BakeOptions o = smallBake();
    ASSERT_TRUE(prepareBakeFolder(dir, o));
    BakeOptions other = o;
    other.tile_size = 64;
    const Status s = prepareBakeFolder(dir, other);
    EXPECT_FALSE(s);
    EXPECT_NE(s.message().find("tile_size 32 there, 64 here"), std::string::npos) << s.message();
    std::ofstream(dir + "/file") << "x";
    EXPECT_FALSE(prepareBakeFolder(dir + "/file/sub/world", o));
    EXPECT_FALSE(fs::exists(dir + "/file/sub"));
    BakeOptions bad = o;
    bad.levels = 9;  // level 7 needed, the source has 0..5
    EXPECT_NE(checkBakeOptions(bad).message().find("levels"), std::string::npos);
    bad = o, bad.shard_index = 4, bad.shard_count = 4;
    EXPECT_NE(checkBakeOptions(bad).message().find("4/4"), std::string::npos);
    bad = o, bad.region.width = 1;
    EXPECT_FALSE(checkBakeOptions(bad));
}

TEST(TilesetBake, ImplicitTilesetWritesSubtreesWithTheTreesAvailability) {
    const std::string dir = test::scratchDir("tileset_implicit");
    BakeOptions o = smallBake();
    o.layout = TilesetLayout::Implicit;
    bakeAll(dir, o, 2);
    const nlohmann::json tileset = nlohmann::json::parse(test::readFile(dir + "/tileset.json"));
    const auto& implicit = tileset["root"]["implicitTiling"];
    const BakeTree tree(o);
    EXPECT_EQ(implicit["availableLevels"].get<int>(), tree.depth());
    EXPECT_EQ(implicit["subdivisionScheme"], "QUADTREE");
    const std::string subtree = test::readFile(dir + "/subtrees/0/0/0.subtree");
    ASSERT_GE(subtree.size(), 24u);
    EXPECT_EQ(subtree.substr(0, 4), "subt");
    uint64_t json_length = 0, binary_length = 0;
    std::memcpy(&json_length, subtree.data() + 8, 8);
    std::memcpy(&binary_length, subtree.data() + 16, 8);
    EXPECT_EQ(24 + json_length + binary_length, subtree.size());
    EXPECT_EQ(json_length % 8, 0u);
    const nlohmann::json j = nlohmann::json::parse(subtree.substr(24, json_length));
    // Root subtree: its tile bits count the root, the empty levels and the content levels it holds.
    const int levels = implicit["subtreeLevels"].get<int>();
    EXPECT_EQ(j["tileAvailability"]["availableCount"].get<int>(), availableTiles(tree, 0, std::min(levels, tree.depth())));
    // The root box's geometric error bounds every tile's measured error once halved per level.
    EXPECT_GT(tileset["root"]["geometricError"].get<double>(), 0.0);
}

TEST(TilesetBake, ExportsAndBakesOnAFullDiskOrReadOnlyFolderFailNamingTheFileAndKeepTheOldOnes) {
    // glTF, heightmap and mask exports and a bake with its merge, as the CLI, the editor and the
    // Python module run them, on a small filesystem of our own (issue 54).
    TERRASYNTH_ON_A_PRIVATE_TMPFS(small, "TilesetBake.ExportsAndBakesOnAFullDiskOrReadOnlyFolderFailNamingTheFileAndKeepTheOldOnes",
                                  "tileset_disk_faults", "24m");
    const Heightfield field = test::crop(test::loadExemplarField("orom_alaska"), 0, 0, 129, 129);
    std::vector<uint8_t> types;
    for (float h : field.heights) types.push_back(h > 2000.0f ? 1 : 0);
    const std::vector<std::string> type_names = {"low", "high"};
    GltfExportOptions gltf;
    gltf.region = {0, 0, field.width, field.height};
    gltf.tile_size = 32;
    const std::string bake = small + "/bake";
    BakeOptions o = smallBake();
    o.heightmaps = HeightmapFormat::GeoTiff;
    auto write_everything = [&]() -> Status {
        if (auto g = exportGltf(small + "/terrain.glb", heightSourceFromField(field), gltf); !g) return g.status();
        if (Status h = exportHeightmap(small + "/terrain.tif", field); !h) return h;
        if (auto m = writeTypeMasks(small + "/mask_", field.width, field.height, types, type_names); !m) return m.status();
        if (Status p = prepareBakeFolder(bake, o); !p) return p;
        if (auto b = bakeTiles(bake, demSource(), o); !b) return b.status();
        if (auto m = mergeTileset(bake); !m) return m.status();
        return Status::ok();
    };
    const Status wrote = write_everything();
    ASSERT_TRUE(wrote) << wrote.message();
    const auto before = folderContents(small);
    ASSERT_GT(before.size(), 20u);
    // The tile the re-bake below is to write again: the last of the last unit.
    const BakeTree tree(o);
    const std::string tile = bake + "/" + tree.tilePath(unitTiles(tree, orderedUnits(tree).back()).back(), ".glb");
    ASSERT_TRUE(fs::exists(tile));

    // Each writer again, one at a time, with the disk full or the folder read-only: the error names
    // the file and says why, the files under their final names are the old ones, nothing else is left.
    auto each_writer_fails = [&](const char* why) {
        const auto g = exportGltf(small + "/terrain.glb", heightSourceFromField(field), gltf);
        ASSERT_FALSE(g);
        EXPECT_NE(g.message().find(small + "/terrain"), std::string::npos) << g.message();
        EXPECT_NE(g.message().find(why), std::string::npos) << g.message();
        const Status h = exportHeightmap(small + "/terrain.tif", field);
        ASSERT_FALSE(h);
        EXPECT_NE(h.message().find(small + "/terrain.tif"), std::string::npos) << h.message();
        const auto m = writeTypeMasks(small + "/mask_", field.width, field.height, types, type_names);
        ASSERT_FALSE(m);
        EXPECT_NE(m.message().find(small + "/mask_"), std::string::npos) << m.message();
        // A new bake: its folder cannot take its plan, and is removed again.
        const Status fresh = prepareBakeFolder(small + "/another_bake", o);
        ASSERT_FALSE(fresh);
        EXPECT_NE(fresh.message().find(small + "/another_bake"), std::string::npos) << fresh.message();
        EXPECT_FALSE(fs::exists(small + "/another_bake"));
        std::printf("%s: %s\n  %s\n  %s\n  %s\n", why, g.message().c_str(), h.message().c_str(), m.message().c_str(),
                    fresh.message().c_str());
    };
    auto intact = [&](const char* when) {
        const auto now = folderContents(small);
        EXPECT_EQ(now.size(), before.size()) << when << ": temporaries left or files gone";
        for (const auto& [name, bytes] : before) {
            const auto it = now.find(name);
            ASSERT_NE(it, now.end()) << when << ": " << name << " is gone";
            EXPECT_TRUE(it->second == bytes) << when << ": " << name << " changed";
        }
    };

    // A tile gone missing (before the disk fills: its bytes would make room for it again).
    const std::string removed_bytes = before.at(fs::relative(tile, small).string());
    ASSERT_TRUE(fs::remove(tile));
    ASSERT_NE(std::system(("dd if=/dev/zero of='" + small + "/filler' bs=64k 2>/dev/null").c_str()), -1);
    each_writer_fails("disk full");
    // The re-bake cannot write the tile back; the rest stays as it was.
    auto rebake = bakeTiles(bake, demSource(), o);
    ASSERT_FALSE(rebake);
    // Named by the tile's files (its .glb or the heightmap beside it, staged together).
    EXPECT_NE(rebake.message().find(fs::path(tile).replace_extension(".").string()), std::string::npos)
        << rebake.message();
    EXPECT_NE(rebake.message().find("disk full"), std::string::npos) << rebake.message();
    std::printf("disk full, re-bake: %s\n", rebake.message().c_str());
    EXPECT_FALSE(fs::exists(tile));
    // With room again the re-bake writes the tile it lost, bit for bit, and only that tile.
    ASSERT_EQ(::unlink((small + "/filler").c_str()), 0);
    auto again = bakeTiles(bake, demSource(), o);
    ASSERT_TRUE(again) << again.message();
    EXPECT_EQ(again->tiles_baked, 1);
    EXPECT_TRUE(test::readFile(tile) == removed_bytes);
    intact("full");  // the tile back, nothing else changed, no temporaries

    ASSERT_EQ(std::system(("mount -o remount,ro '" + small + "'").c_str()), 0);
    each_writer_fails("Read-only file system");
    intact("read-only");
}
