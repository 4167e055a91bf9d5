// terrasynth_plugin/height_source.h: where tile heights come from.
//
// The tile manager only needs "heights of a window of the global grid at a level": a
// terrasynth::HeightSource (terrasynth/grid.h, the contract of Terrain::heights and
// EditSession::heightSource). This header adds sources that need no synthesis.
#pragma once

#include <functional>
#include <memory>

#include "terrasynth/grid.h"

namespace terrasynth::plugin {

using terrasynth::HeightSource;

// A real DEM repeated without seams over the unbounded plane (mirrored every other period), for
// viewing an exemplar and for tests that must not depend on synthesis. Level k sample (X, Y) is the
// mean of the level-0 block [X*2^k, (X+1)*2^k) x [Y*2^k, (Y+1)*2^k), so any window is bit-identical
// to the same samples of a larger window. Levels above log2(2*min(width, height)) are refused.
// The field is copied; the source is immutable and thread-safe.
HeightSource mirroredExemplarSource(const Heightfield& exemplar);

// Wraps `base` so that `edit(window, level, heights)` post-processes every result (tests use it to
// model a local edit). `edit` must be thread-safe and deterministic per sample.
HeightSource editedSource(HeightSource base,
                          std::function<void(const PixelWindow&, int level, Heightfield&)> edit);

// Wraps `base` so that a tile-sized window (each side at least group_side / 8) lying within one
// aligned group (the global square [gx, gx + 1) * group_side of its level, plus 8 samples on every
// side) is cut from that group's heights, asked of `base` once: neighbouring tiles then share one
// synthesis and its margins instead of paying them each (with drainage by breaching a 64^2 tile
// cost 7.7 times its undrained synthesis). Other windows go to `base` as they are. Exact only for
// a source that keeps its contract (grid.h: overlapping windows bit-identical) and never changes:
// a terrain opened read-only, not an edit session's source. The most recent `max_groups` groups
// are kept (each (group_side + 17)^2 floats); two threads asking for one group wait for one
// computation. A group that fails leaves the window to `base`. group_side < 8 or max_groups 0:
// `base` itself. Thread-safe if `base` is.
HeightSource groupedSource(HeightSource base, int group_side, size_t max_groups);

// groupedSource for tiles of `tile_size` quads: groups of 4 x 4 tiles up to 512 samples a side,
// 2 x 2 above, as many as 64 MB hold (at least 8); tiles of 1024 quads and more: `base` itself.
HeightSource tileGroupedSource(HeightSource base, int tile_size);

}  // namespace terrasynth::plugin
