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

}  // namespace terrasynth::plugin
