// terrasynth/limits.h: every input limit and cost limit of the runtime, in one place.
//
// Readers check these against what a file *claims* (a PNG header, a sidecar, a database section
// length, a JSON array's size) before allocating or computing anything, so a small hostile file can
// neither exhaust memory nor make the work explode; a rejected input gets an error naming the file,
// the field and the limit. docs/limits.md lists them for users (constraint limits also in
// docs/project-format.md). Raising one is a design decision: check what it costs first.
#pragma once

#include <cstdint>

namespace terrasynth::limits {

// ---- Files ----
// Largest file any reader loads into memory (databases are the largest legitimate inputs).
constexpr uint64_t kMaxFileBytes = uint64_t(4) << 30;  // 4 GiB
// JSON texts (projects, sidecars, layer files): size and nesting depth. Depth 64 leaves room for
// 30 nested layer groups; the parser and every later copy of the tree stay shallow.
constexpr uint64_t kMaxJsonBytes = uint64_t(256) << 20;  // 256 MiB
constexpr int kMaxJsonDepth = 64;

// ---- Heights ----
// Any height or height offset a file carries (databases, edited-heights sidecars): finite and
// within +-100 km, so no mesher, skirt or statistic ever meets a NaN or an infinity from a file.
constexpr float kMaxAbsHeightM = 1e5f;

// ---- Images (exemplars, heightmaps, masks) ----
constexpr int kMaxImageSide = 65536;                       // pixels per side
constexpr uint64_t kMaxImagePixels = uint64_t(1) << 28;    // 268 M samples (1 GiB of float heights)
// zlib's deflate expands at most 1032:1 (RFC 1951 stored/Huffman limits), so a PNG whose header
// claims more decoded bytes than 1032 x its file size cannot be honest and is refused unread.
constexpr uint64_t kMaxDeflateExpansion = 1032;

// ---- Database builds ----
// Level-0 pixels of all exemplars after resampling to the common spacing (memory while building is
// about 140 bytes per pixel; a built database about 25).
constexpr uint64_t kMaxDatabasePixels = uint64_t(1) << 25;  // 33.5 M pixels

// ---- Grid ----
// Output windows: 1..16384 pixels per side, origin within +-2^29 at any level (synthesis_plan.h).
constexpr int kMaxWindowSide = 16384;
constexpr int64_t kMaxWindowOrigin = int64_t(1) << 29;
// A project's origin (and its constraints' coordinates, relative to it) stay within +-2^28, so the
// extent, every constraint site and every synthesis margin fit the window limit above.
constexpr int64_t kMaxProjectOrigin = int64_t(1) << 28;
constexpr double kMaxConstraintCoordinate = double(int64_t(1) << 28);

// ---- 3D Tiles bakes (docs/bake.md) ----
// A bake's region lies within +-kMaxProjectOrigin (so every window it synthesizes fits the grid)
// and holds at most this many level-0 samples (262144^2; about a day of CPU time) and this many
// tiles (the plan, the merge and the tileset hold a record of each).
constexpr uint64_t kMaxBakeSamples = uint64_t(1) << 36;
constexpr int64_t kMaxBakeTiles = int64_t(1) << 22;

// ---- Constraints (docs/project-format.md) ----
// Point lifting synthesizes every site each round, grouped into shared windows; 20000 points over a
// 1024^2 extent take a few whole-extent syntheses per round.
constexpr int kMaxPointConstraints = 20000;
constexpr int kMaxCurves = 1000;
constexpr int kMaxCoursePoints = 10000;    // per curve
constexpr int kMaxCurveWidgets = 1000;     // per curve
// Sum of all courses' lengths (level-0 pixels): courses are sampled every pixel and every sample is
// visited per synthesized level.
constexpr double kMaxTotalCourseLengthPx = double(1 << 20);
// Crossings between courses (each pins a junction, s3): beyond this the courses are a scribble.
constexpr int kMaxJunctions = 16384;
constexpr int kMaxStrokes = 10000;             // type strokes, and freeze strokes, each
constexpr int kMaxStrokePoints = 100000;       // per stroke
// Work of painting one stroke (terrasynth::strokePaintCost: brush dabs that reach the extent times
// the rows they cover, plus the extent): about a second at the limit.
constexpr uint64_t kMaxStrokePaintCost = uint64_t(1) << 30;
constexpr int kMaxPastes = 256;
constexpr int kMaxPastePolygonPoints = 10000;  // per paste source polygon

// ---- Layers (docs/layers.md) ----
constexpr int kMaxLayers = 1000;     // edit layers, counting every group's children
constexpr int kMaxGroupDepth = 16;   // groups inside groups
constexpr int kMaxRidgePoints = 10000;
// Pixel visits of one ridge (each segment's reach over the grid; terrasynth::ridgeReliefCost), and
// of one perspective stroke's ridge: a few seconds at the limit.
constexpr uint64_t kMaxRidgeCost = uint64_t(1) << 31;
// Hole fill: picks of one layer's lineage (each a generation of three quilts), and the pixel visits
// of the whole lineage (terrasynth::holeFillCost): about half a minute at the limit.
constexpr int kMaxHoleFillPicks = 64;
constexpr uint64_t kMaxHoleFillCost = uint64_t(1) << 34;

}  // namespace terrasynth::limits
