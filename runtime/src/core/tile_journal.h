// Private: an undo journal for 2-D arrays edited in place (the incremental synthesis history, the
// edited heights, painted masks), recorded by 32x32 tiles so a step costs what it touched, not the
// whole array.
//
// Before writing a rectangle of a plane, call record(): tiles of it not yet saved in this journal are
// copied. swap() exchanges the saved tiles with the planes' current content, so the same call undoes
// a step and, applied again, redoes it; the journal then holds the other state.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <unordered_set>
#include <vector>

namespace terrasynth::detail {

// A row-major array of width*height elements of elem_bytes bytes each.
struct JournalPlane {
    void* data = nullptr;
    int width = 0, height = 0;
    int elem_bytes = 0;
};

class TileJournal {
public:
    static constexpr int kTile = 32;

    // Saves the tiles of plane `id` overlapping [x, x+w) x [y, y+h) (clipped to the plane) that this
    // journal has not saved yet.
    void record(int id, const JournalPlane& plane, int64_t x, int64_t y, int64_t w, int64_t h);
    // Exchanges every saved tile with the current content of its plane (looked up by id).
    void swap(const std::function<JournalPlane(int id)>& plane_of);
    // Adds the tiles of a journal recorded after this one that this one has not saved: the merged
    // journal undoes both steps at once.
    void absorb(TileJournal&& later);
    bool empty() const { return tiles_.empty(); }
    // Bytes held by saved tiles.
    size_t bytes() const { return bytes_; }

private:
    struct Tile {
        uint64_t key;
        int plane, x0, y0, w, h;  // element rectangle of the tile, clipped to its plane
        std::vector<uint8_t> saved;
    };
    std::vector<Tile> tiles_;
    std::unordered_set<uint64_t> seen_;
    size_t bytes_ = 0;
};

}  // namespace terrasynth::detail
