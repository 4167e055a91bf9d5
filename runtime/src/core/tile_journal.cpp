#include "core/tile_journal.h"

#include <algorithm>
#include <cstring>

namespace terrasynth::detail {

void TileJournal::record(int id, const JournalPlane& plane, int64_t x, int64_t y, int64_t w, int64_t h) {
    const int64_t x0 = std::max<int64_t>(0, x), y0 = std::max<int64_t>(0, y);
    const int64_t x1 = std::min<int64_t>(plane.width, x + w), y1 = std::min<int64_t>(plane.height, y + h);
    if (x1 <= x0 || y1 <= y0) return;
    const size_t row_bytes = static_cast<size_t>(plane.width) * plane.elem_bytes;
    for (int64_t ty = y0 / kTile; ty <= (y1 - 1) / kTile; ++ty)
        for (int64_t tx = x0 / kTile; tx <= (x1 - 1) / kTile; ++tx) {
            const uint64_t key = (static_cast<uint64_t>(id) << 48) ^ (static_cast<uint64_t>(ty) << 24) ^ static_cast<uint64_t>(tx);
            if (!seen_.insert(key).second) continue;
            Tile t;
            t.key = key;
            t.plane = id;
            t.x0 = static_cast<int>(tx * kTile), t.y0 = static_cast<int>(ty * kTile);
            t.w = std::min(kTile, plane.width - t.x0), t.h = std::min(kTile, plane.height - t.y0);
            const size_t tile_row = static_cast<size_t>(t.w) * plane.elem_bytes;
            t.saved.resize(tile_row * t.h);
            const auto* base = static_cast<const uint8_t*>(plane.data);
            for (int r = 0; r < t.h; ++r)
                std::memcpy(&t.saved[r * tile_row], base + (t.y0 + r) * row_bytes + static_cast<size_t>(t.x0) * plane.elem_bytes,
                            tile_row);
            bytes_ += t.saved.size();
            tiles_.push_back(std::move(t));
        }
}

void TileJournal::absorb(TileJournal&& later) {
    for (Tile& t : later.tiles_) {
        if (!seen_.insert(t.key).second) continue;
        bytes_ += t.saved.size();
        tiles_.push_back(std::move(t));
    }
    later.tiles_.clear();
    later.seen_.clear();
    later.bytes_ = 0;
}

void TileJournal::swap(const std::function<JournalPlane(int id)>& plane_of) {
    std::vector<uint8_t> row;
    for (Tile& t : tiles_) {
        const JournalPlane plane = plane_of(t.plane);
        const size_t row_bytes = static_cast<size_t>(plane.width) * plane.elem_bytes;
        const size_t tile_row = static_cast<size_t>(t.w) * plane.elem_bytes;
        auto* base = static_cast<uint8_t*>(plane.data);
        for (int r = 0; r < t.h; ++r) {
            uint8_t* live = base + (t.y0 + r) * row_bytes + static_cast<size_t>(t.x0) * plane.elem_bytes;
            std::swap_ranges(live, live + tile_row, &t.saved[r * tile_row]);
        }
    }
}

}  // namespace terrasynth::detail
