// Subtree files of an implicit quadtree (3D Tiles 1.1, "Implicit Tiling"): per subtree, tile and
// content availability over its levels and the availability of the child subtrees below it, each a
// bitstream in Morton order (x in the low bit), or a constant when all bits agree.
#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "export/tileset_implicit.h"
#include "terrasynth/heightfield_io.h"

namespace terrasynth::bake_detail {

namespace fs = std::filesystem;

namespace {

struct Bitstream {
    std::vector<uint8_t> bytes;
    size_t bits = 0, set = 0;
    void push(bool on) {
        if (bits % 8 == 0) bytes.push_back(0);
        if (on) bytes.back() |= uint8_t(1u << (bits % 8)), ++set;
        ++bits;
    }
};

void deinterleave(uint64_t m, int64_t* x, int64_t* y) {
    *x = *y = 0;
    for (int b = 0; b < 32; ++b) {
        *x |= int64_t((m >> (2 * b)) & 1) << b;
        *y |= int64_t((m >> (2 * b + 1)) & 1) << b;
    }
}

class SubtreeWriter {
public:
    SubtreeWriter(const std::string& folder, const BakeTree& tree, int levels)
        : folder_(folder), tree_(tree), levels_(levels) {}

    Status write(const ImplicitCoord& root) {
        Bitstream tiles, content, children;
        for (int l = 0; l < levels_; ++l)
            for (uint64_t m = 0; m < (uint64_t(1) << (2 * l)); ++m) {
                const ImplicitCoord c = at(root, l, m);
                const bool available = c.depth < tree_.depth() && implicitTileAvailable(tree_, c);
                tiles.push(available);
                content.push(available && c.depth >= tree_.emptyLevels());
            }
        std::vector<ImplicitCoord> below;
        for (uint64_t m = 0; m < (uint64_t(1) << (2 * levels_)); ++m) {
            const ImplicitCoord c = at(root, levels_, m);
            const bool available = c.depth < tree_.depth() && implicitTileAvailable(tree_, c);
            children.push(available);
            if (available) below.push_back(c);
        }
        if (Status s = writeFile(root, tiles, content, children); !s) return s;
        for (const ImplicitCoord& c : below)
            if (Status s = write(c); !s) return s;
        return Status::ok();
    }

private:
    static ImplicitCoord at(const ImplicitCoord& root, int level, uint64_t morton) {
        int64_t x, y;
        deinterleave(morton, &x, &y);
        return {root.depth + level, (root.x << level) + x, (root.y << level) + y};
    }

    // {"constant": b} when every bit agrees, else a bitstream in its own 8-byte aligned bufferView.
    nlohmann::json availability(const Bitstream& b, nlohmann::json& views, std::string& binary) const {
        if (b.set == 0 || b.set == b.bits) return {{"constant", b.set ? 1 : 0}, {"availableCount", b.set}};
        binary.append((8 - binary.size() % 8) % 8, '\0');
        views.push_back({{"buffer", 0}, {"byteOffset", binary.size()}, {"byteLength", b.bytes.size()}});
        binary.append(b.bytes.begin(), b.bytes.end());
        return {{"bitstream", views.size() - 1}, {"availableCount", b.set}};
    }

    Status writeFile(const ImplicitCoord& root, const Bitstream& tiles, const Bitstream& content, const Bitstream& children) {
        nlohmann::json j, views = nlohmann::json::array();
        std::string binary;
        j["tileAvailability"] = availability(tiles, views, binary);
        j["contentAvailability"] = nlohmann::json::array({availability(content, views, binary)});
        j["childSubtreeAvailability"] = availability(children, views, binary);
        binary.append((8 - binary.size() % 8) % 8, '\0');
        if (!binary.empty()) {
            j["buffers"] = nlohmann::json::array({{{"byteLength", binary.size()}}});
            j["bufferViews"] = views;
        }
        std::string text = j.dump();
        text.append((8 - text.size() % 8) % 8, ' ');
        std::string file = "subt";
        auto le = [&file](uint64_t v, int bytes) {
            for (int k = 0; k < bytes; ++k) file.push_back(char((v >> (8 * k)) & 0xFF));
        };
        le(1, 4);
        le(text.size(), 8);
        le(binary.size(), 8);
        file += text;
        file += binary;
        const std::string path = folder_ + "/subtrees/" + std::to_string(root.depth) + "/" + std::to_string(root.x) + "/" +
                                 std::to_string(root.y) + ".subtree";
        std::error_code ec;
        fs::create_directories(fs::path(path).parent_path(), ec);
        if (ec) return Status::error(path + ": cannot create its folder (" + ec.message() + ")");
        return writeFileAtomically(path, file);
    }

    const std::string& folder_;
    const BakeTree& tree_;
    const int levels_;
};

}  // namespace

int subtreeLevels(int depth) {
    const int parts = (depth + 5) / 6;
    return (depth + parts - 1) / parts;
}

bool implicitTileAvailable(const BakeTree& tree, const ImplicitCoord& c) {
    const int64_t side = int64_t(1) << c.depth;
    if (c.depth < 0 || c.x < 0 || c.y < 0 || c.x >= side || c.y >= side) return false;
    if (c.depth >= tree.emptyLevels()) return tree.exists(tree.tileAt(c));
    // Above the coarsest LOD: available when its cells at the coarsest depth meet the coarsest tiles,
    // which fill columns [0, count_i) and, counting y from the south, rows [side_n - count_j, side_n).
    const IndexRange& top = tree.range(tree.levels() - 1);
    const int shift = tree.emptyLevels() - c.depth;
    const int64_t side_n = int64_t(1) << tree.emptyLevels();
    const int64_t x0 = c.x << shift, x1 = (c.x + 1) << shift, y0 = c.y << shift, y1 = (c.y + 1) << shift;
    return x0 < top.countI() && y1 > side_n - top.countJ() && x1 > 0 && y0 < side_n;
}

Status writeSubtrees(const std::string& folder, const BakeTree& tree, int subtree_levels) {
    return SubtreeWriter(folder, tree, subtree_levels).write({0, 0, 0});
}

}  // namespace terrasynth::bake_detail
