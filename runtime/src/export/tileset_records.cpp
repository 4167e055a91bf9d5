// Unit records (units/<lod>/<i>/<j>.json): what the shard that finished a unit found on disk, each
// file of its tiles with its size and digest, so a re-run and the merge can tell a whole tile from a
// damaged one. A record depends only on the plan and the bytes, so duplicate shards (a requeued job
// running beside its first attempt) write the same record, and a sharded bake's records are a
// single-process bake's.
#include <filesystem>

#include "core/digest.h"
#include "core/json_reader.h"
#include "export/tileset_plan.h"
#include "terrasynth/heightfield_io.h"

namespace terrasynth::bake_detail {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

constexpr const char* kRecordFormat = "terrasynth-bake-unit";

// The unit's files in the order tileFiles gives them, tile by tile.
std::vector<std::string> unitFiles(const BakeTree& tree, const BakeOptions& o, const BakeUnit& unit) {
    std::vector<std::string> files;
    for (const TileKey& t : unitTiles(tree, unit))
        for (std::string& f : tileFiles(tree, o, t)) files.push_back(std::move(f));
    return files;
}

bool isGlb(const std::string& path) { return path.size() > 4 && path.compare(path.size() - 4, 4, ".glb") == 0; }

}  // namespace

std::string unitRecordPath(const BakeUnit& unit) {
    return "units/" + std::to_string(unit.lod) + "/" + std::to_string(unit.i) + "/" + std::to_string(unit.j) + ".json";
}

BakeUnit unitOf(const TileKey& t) {
    if (t.lod >= 2) return {t.lod, t.i, t.j, 0.0};
    if (t.lod == 1) return {1, t.i, t.j, 0.0};
    return {1, floorDiv(t.i, 2), floorDiv(t.j, 2), 0.0};
}

Result<RecordedFiles> readUnitRecord(const std::string& folder, const BakeTree& tree, const BakeOptions& o,
                                     const BakeUnit& unit) {
    const std::string path = folder + "/" + unitRecordPath(unit);
    auto bytes = readFileBytes(path, limits::kMaxJsonBytes);
    if (!bytes) return bytes.status();
    auto parsed = detail::parseJson(*bytes, path);
    if (!parsed) return parsed.status();
    detail::JsonReader r(*parsed, "");
    if (r.string("format", "") != kRecordFormat) r.fail("format", std::string("must be \"") + kRecordFormat + "\"");
    if (r.integer("version", 0, 1, 1) != 1) r.fail("version", "must be 1");
    const json* files = r.child("files");
    const std::vector<std::string> expected = unitFiles(tree, o, unit);
    if (r.ok() && (!files || !files->is_array() || files->size() != expected.size()))
        r.fail("files", "must list the " + std::to_string(expected.size()) + " files of the unit's tiles");
    RecordedFiles out;
    for (size_t k = 0; r.ok() && k < expected.size(); ++k) {
        const json& f = (*files)[k];
        uint64_t digest = 0;
        const bool ok = f.is_array() && f.size() == 3 && f[0].is_string() && f[0].get<std::string>() == expected[k] &&
                        f[1].is_number_unsigned() && f[2].is_string() &&
                        detail::parseDigestText(f[2].get<std::string>(), &digest);
        if (!ok) r.fail("files[" + std::to_string(k) + "]", "must be [\"" + expected[k] + "\", bytes, \"16 hex digits\"]");
        else out[expected[k]] = {static_cast<int64_t>(f[1].get<uint64_t>()), digest};
    }
    if (Status s = r.finish(); !s) return s.withContext(path);
    return out;
}

Status writeUnitRecord(const std::string& folder, const BakeTree& tree, const BakeOptions& o, const BakeUnit& unit,
                       const RecordedFiles& known) {
    // One line per file, so a record reads (and diffs) as a list.
    std::string text = std::string("{\"format\": \"") + kRecordFormat + "\", \"version\": 1, \"files\": [";
    const std::vector<std::string> files = unitFiles(tree, o, unit);
    for (const std::string& f : files) {
        FileDigest d;
        if (auto it = known.find(f); it != known.end()) {
            d = it->second;
        } else {
            auto bytes = readFileBytes(folder + "/" + f);
            if (!bytes) return bytes.status();
            d = {static_cast<int64_t>(bytes->size()), detail::fnv1a(bytes->data(), bytes->size())};
        }
        text += std::string(&f == &files.front() ? "\n" : ",\n") + " " +
                detail::dumpJson(json::array({f, d.bytes, detail::digestText(d.digest)}));
    }
    text += "\n]}\n";
    const std::string path = folder + "/" + unitRecordPath(unit);
    std::error_code ec;
    fs::create_directories(fs::path(path).parent_path(), ec);
    if (ec) return Status::error(path + ": cannot create the folder (" + ec.message() + ")");
    return writeFileAtomically(path, text);
}

Result<FileDigest> verifyTileFile(const std::string& folder, const std::string& file, const TileKey& tile,
                                  const FileDigest* recorded, TileRecord* glb_record) {
    const std::string path = folder + "/" + file;
    auto bytes = readFileBytes(path);
    if (!bytes) return Status::error(file + ": missing or unreadable (" + bytes.message() + ")");
    const FileDigest found{static_cast<int64_t>(bytes->size()), detail::fnv1a(bytes->data(), bytes->size())};
    if (recorded && recorded->bytes != found.bytes)
        return Status::error(file + ": " + std::to_string(found.bytes) + " bytes, the shard recorded " +
                             std::to_string(recorded->bytes));
    if (recorded && recorded->digest != found.digest)
        return Status::error(file + ": digest " + detail::digestText(found.digest) + ", the shard recorded " +
                             detail::digestText(recorded->digest) + " (changed or damaged since it was baked)");
    if (isGlb(file)) {
        auto record = tileRecordFromGlb(*bytes, file);
        if (!record) return record.status();
        if (!(record->key == tile)) return Status::error(file + ": holds another tile (a file moved?)");
        if (glb_record) *glb_record = *record;
    }
    return found;
}

}  // namespace terrasynth::bake_detail
