// Small RGBA pictures of heightfields for the panels (exemplar thumbnails, hole-fill previews).
#pragma once

#include <cstdint>
#include <vector>

#include "terrasynth/database.h"
#include "terrasynth/heightfield.h"

namespace terrasynth::editor {

struct Picture {
    int width = 0, height = 0;
    std::vector<uint8_t> rgba;  // row 0 at the top (north)
};

// Hillshade (sun north-west, 45 degrees) over a tint of the field's own height range, box-filtered
// down so the longer side is at most `max_side` pixels.
Picture hillshadePicture(const Heightfield& field, int max_side);

// An exemplar's level-0 heights as the database holds them (its atlas rectangle).
Heightfield exemplarHeights(const ExemplarDatabase& db, int exemplar);

}  // namespace terrasynth::editor
