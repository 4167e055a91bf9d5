// tile_builder.h: one quadtree tile from heights to its data model and a detached OSG subgraph.
//
// This is the whole per-tile job a worker thread runs (osgEarth REX style "create the tile model off
// the draw thread, merge it later"): read the tile's window (plus an apron so normals are central
// differences across tile edges) into its TileData, mesh it with skirts (terrasynth/mesh.h), and
// wrap the mesh in an osg::MatrixTransform + osg::Geometry that no scene graph references yet, so
// building it touches no shared state. The UPDATE traversal later only attaches or swaps the
// finished node.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <osg/BoundingBox>
#include <osg/Node>
#include <osg/ref_ptr>

#include "terrasynth/mesh.h"
#include "terrasynth_plugin/height_source.h"
#include "terrasynth_plugin/terrain_look.h"
#include "terrasynth_plugin/tile_key.h"
#include "tile_data.h"

namespace terrasynth::plugin {

struct TileBuildSettings {
    TileLayout layout;
    // Grid step in samples (1 = every sample). tile_size must be a multiple of it.
    int mesh_step = 1;
    // Skirts hang (tile height range + skirt_extra_spacings * level spacing) below the edges: deep
    // enough to cover the gap to any coarser or finer neighbour, whose edge lies in the same relief.
    float skirt_extra_spacings = 2.0f;
    // Reorder for the vertex cache (meshoptimizer); costs build time, saves draw time.
    bool optimize_order = false;
    // Geomorphing: also take the parent level's samples under the tile (a quarter of the tile's
    // samples) and give every vertex its height on the parent's surface. Tiles at max_level have no
    // parent and do not morph. Needs an even tile_size / mesh_step.
    bool geomorph = false;
    int max_level = 0;
};

struct TileBuild {
    TileKey key;
    uint64_t generation = 0;  // the edit generation the heights were read at (set by the caller)
    Status status = Status::ok();
    // The data model: what the tile was built from. Null when `status` is an error.
    std::shared_ptr<const TileData> data;
    // The render model: a MatrixTransform (world offset of the tile's north-west corner, in double)
    // over one Geometry whose vertices are relative to that corner, so float precision holds anywhere
    // in an unbounded world. Bounds are already computed.
    osg::ref_ptr<osg::Node> node;
    osg::BoundingBox box;      // world frame, including the skirt
    size_t bytes = 0;          // client-side vertex and index memory of the node
    size_t triangles = 0;      // drawn per frame when the tile is drawn (skirts included)
    double heights_ms = 0.0, mesh_ms = 0.0, osg_ms = 0.0;
};

// The window (global pixels of key.level) a tile reads: its (tile_size + 1)^2 samples plus an apron
// of mesh_step samples on every side.
PixelWindow tileReadWindow(const TileKey& key, const TileBuildSettings& settings);

// Builds one tile. Thread-safe if `source` (and `types`) are. Errors (source failure, wrong window
// size) come back in `status` with the tile key in the message. For geomorphing, `parent` (the
// resident parent's data, built with the same settings) saves reading the parent level from
// `source`; null = read it. With `types`, the data keeps every sample's terrain type id and every
// vertex carries it (kTypeAttribute) for type colours.
TileBuild buildTile(const HeightSource& source, const TileKey& key, const TileBuildSettings& settings,
                    const TileData* parent = nullptr, const TypeSource* types = nullptr);

// The detached OSG subgraph for a mesh whose vertices are relative to (origin_x, origin_y).
// Copies the mesh into VBO-backed arrays; STATIC data variance (edits swap whole tiles).
// With `parent_heights` (one per vertex) the geometry carries them as the vertex attribute
// kCoarseHeightAttribute and the uniform "ts_parent_spacing" = parent_spacing for the morph shader;
// with `type_ids` (one per vertex) the attribute kTypeAttribute.
osg::ref_ptr<osg::Node> makeTileNode(const TileMesh& mesh, double origin_x, double origin_y, size_t* bytes,
                                     const std::vector<float>* parent_heights = nullptr, double parent_spacing = 0.0,
                                     const std::vector<float>* type_ids = nullptr);

// Per vertex of `mesh` (vertices relative to the tile's north-west corner, `spacing` metres between
// samples, grid step `step`, skirt `skirt_depth_m`), the height of the parent tile's mesh at the same
// x, y. `parent` holds the parent level's samples under the tile: (tile_size/2 + 1)^2.
std::vector<float> parentSurfaceHeights(const TileMesh& mesh, const Heightfield& parent, double spacing, int step,
                                        float skirt_depth_m);

}  // namespace terrasynth::plugin
