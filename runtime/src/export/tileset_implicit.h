// Private: 3D Tiles 1.1 implicit tiling for a bake (tileset_implicit.cpp): the tree's availability
// as subtree files.
#pragma once

#include <string>

#include "export/tileset_plan.h"

namespace terrasynth::bake_detail {

constexpr const char* kSubtreeTemplate = "subtrees/{level}/{x}/{y}.subtree";

// Levels per subtree file: the tree's depth cut into the fewest parts of at most 6 levels, evenly.
int subtreeLevels(int depth);

// Whether implicit tile (depth, x, y) exists: a content tile of the tree, or an empty tile above the
// coarsest LOD with some content below it.
bool implicitTileAvailable(const BakeTree& tree, const ImplicitCoord& c);

// Writes subtrees/<d>/<x>/<y>.subtree (binary, version 1) for every available subtree root.
Status writeSubtrees(const std::string& folder, const BakeTree& tree, int subtree_levels);

}  // namespace terrasynth::bake_detail
