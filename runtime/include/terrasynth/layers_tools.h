// terrasynth/layers_tools.h: the editing tools of Bradbury et al. 2014 (s3.1, s4), each of which
// produces the content of one layer. Geometry is in pixels of the terrain grid (x east, y south,
// pixel centres at integer coordinates), heights in metres.
//
// These are plain functions for tools, previews and tests; the layer stack (layers.h) calls them
// and blends their results in the Laplacian pyramid. All are deterministic functions of their
// arguments (seeded randomness included) and re-entrant.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "terrasynth/heightfield.h"
#include "terrasynth/status.h"

namespace terrasynth {

// ---- Fractal noise (s3.1: "random elevation map generated using standard procedural methods") ----

enum class FractalKind { Fbm, DiamondSquare };

struct FractalParams {
    FractalKind kind = FractalKind::Fbm;
    uint64_t seed = 1;
    double amplitude_m = 500.0;   // standard scale of the relief: heights span about +-amplitude_m
    double offset_m = 0.0;        // added to every height
    double wavelength_px = 256.0; // largest feature size (fBm first octave; diamond-square first step), >= 2
    int octaves = 8;              // fBm only, 1..16
    double gain = 0.5;            // fBm amplitude ratio between octaves, (0, 1)
    double lacunarity = 2.0;      // fBm frequency ratio between octaves, [1.5, 4]
    double roughness = 0.5;       // diamond-square Hurst-like exponent H in (0, 1]: displacement *= 2^-H per step
};
// Message names the offending field, e.g. "octaves: must be in 1..16".
Status validateFractal(const FractalParams& p);
// A w x h field of fractal heights at the given spacing. Gradient-noise fBm or seeded diamond-square
// (Fournier et al. 1982) on the smallest 2^n+1 lattice covering the grid.
Heightfield fractalHeightfield(const FractalParams& p, int width, int height, double meters_per_pixel);

// ---- Regions (masks of paste, hole fill and local noise) ----

enum class RegionShape { Ellipse, Rect };
struct Region {
    RegionShape shape = RegionShape::Ellipse;
    double x = 0, y = 0, width = 0, height = 0;  // bounding rectangle, pixels; the ellipse is inscribed
};
// Coverage in [0,1] per pixel (w*h): 1 inside, 0 outside, with a linear ramp `feather_px` wide
// inside the edge (0 = hard edge with 1-pixel antialiasing).
std::vector<float> regionMask(const Region& region, double feather_px, int width, int height);

// ---- Peaks (s4.2) ----

// A peak whose cross-section along `skew_azimuth_deg` is a two-piece generalised Gaussian whose
// first moments, read as a distribution, are exactly: standard deviation `spread_px`, skewness
// `skewness` and excess kurtosis `kurtosis`. Across that axis the profile is the symmetric
// generalised Gaussian with the same spread and shape. The summit (height_m) is at the centre.
struct PeakParams {
    double center_x = 0, center_y = 0;  // pixels
    double height_m = 500.0;            // summit height above the terrain below; negative digs a pit
    double spread_px = 32.0;            // > 0
    double skewness = 0.0;              // |s| < 0.9; > 0 puts the long gentle flank toward the azimuth
    double kurtosis = 0.0;              // excess kurtosis in [-1.1, 6]: < 0 mesa-like, > 0 needle-like
    double skew_azimuth_deg = 0.0;      // 0 = east, 90 = south
};
// Solved shape: the profile is height * exp(-(t)^beta) with t the scaled elliptic radius.
struct PeakShape {
    double beta = 2.0;          // generalised Gaussian exponent
    double scale_forward = 0;   // pixels, along +azimuth
    double scale_backward = 0;  // pixels, along -azimuth
    double scale_side = 0;      // pixels, across
};
// Errors name the field: "skewness: ..." when (skewness, kurtosis) is outside the family's range.
Result<PeakShape> solvePeakShape(const PeakParams& p);
// Distance from the summit, across the skew axis, at which the peak falls to `fraction` of its height.
double peakFootprintRadius(const PeakParams& p, const PeakShape& shape, double fraction = 0.01);
// The additive relief of the peak (zero beyond 1e-6 of its height).
Result<Heightfield> peakRelief(const PeakParams& p, int width, int height, double meters_per_pixel);

// ---- Ridges (s4.2: ridge line sketched on the heightfield plus a sketched height profile) ----

struct RidgeParams {
    std::vector<std::array<double, 2>> points;  // ridge line, >= 2 points, pixels
    // Crest heights (metres above the terrain below) at evenly spaced arc-length positions from the
    // first to the last point; one value = constant height. Linear in between.
    std::vector<double> profile_m;
    double width_px = 24.0;  // standard deviation of the Gaussian cross-section (Belhadj & Audibert 2005)
};
// 2..limits::kMaxRidgePoints finite points within 1e6 pixels, 1..100000 profile heights within
// 10 km, width in (0, 10000].
Status validateRidge(const RidgeParams& p);
// Additive relief: for each segment, crest(s) * exp(-d^2 / 2 width^2); segments combine by maximum.
// Precondition: validateRidge(p).
Heightfield ridgeRelief(const RidgeParams& p, int width, int height, double meters_per_pixel);
// The pixel visits ridgeRelief makes on a width x height grid (each segment's reach clipped to the
// grid), in O(points): layer stacks refuse ridges above limits::kMaxRidgeCost.
uint64_t ridgeReliefCost(const RidgeParams& p, int width, int height);

// ---- Texture transfer: copy-paste (s4.3) ----

enum class PasteBlend {
    MaxGradient,  // per pyramid coefficient, keep the stronger of source and destination (the paper)
    Replace,      // multi-band spline: source replaces destination inside the mask
};
struct PasteParams {
    std::string source = "terrain";  // "terrain" (the layers below) or a DEM file readExemplar() reads
    double source_x = 0, source_y = 0;  // top-left of the copied rectangle in the source, pixels at
                                        // the terrain spacing (external DEMs are resampled first)
    Region dest;                     // where it lands (shape and size), terrain pixels
    PasteBlend blend = PasteBlend::MaxGradient;
    bool match_height = true;        // shift the source so its mean under the mask equals the destination's
    double vertical_scale = 1.0;     // multiplies the source relief about its masked mean, (0, 10]
    double feather_px = 0.0;         // mask ramp; the pyramid already blends each band over its own scale
};

// ---- Hole fill by quilting (s4.4) ----

struct HoleFillParams {
    Region hole;
    int patch_px = 24;        // quilting block size, 8..128
    int overlap_px = 8;       // block overlap, 2..patch_px/2
    uint64_t seed = 1;
    int candidates = 400;     // random source blocks scored per block, 16..20000
    // Lineage of the artist's picks: generation 0 synthesises 3 variants from scratch and picks
    // choices[0]; each following generation re-synthesises 3 variants guided by the previous pick and
    // picks choices[k]. Values 0..2, at least one, at most limits::kMaxHoleFillPicks.
    std::vector<int> choices = {0};
    double guide_weight = 0.5;  // re-synthesis: share of the block cost given to the guide, [0, 1)
};
// Binary hole mask (1 = hole) for the params' region.
std::vector<uint8_t> holeMask(const HoleFillParams& p, int width, int height);
// `count` variants of `terrain` with the hole re-synthesised by image quilting (Efros & Freeman 2001)
// in spiral order from the rim inward, so the patch-matching error is spread over the region instead
// of piling up at the far boundary (s4.4). Blocks are copied from the terrain outside the hole with a
// height offset; each block is joined along minimum-error boundary cuts. With `guide`, blocks are
// also scored against the blurred guide (the re-synthesis "starting point" of s4.4).
// Variant k uses seed (p.seed, generation, k). Errors: hole empty, touching everything, or no source
// block fits outside it.
Result<std::vector<Heightfield>> holeFillVariants(const Heightfield& terrain, const HoleFillParams& p,
                                                  int generation, const Heightfield* guide, int count = 3);
// Runs the whole lineage in p.choices and returns the final pick. Errors also: a lineage costing
// more than limits::kMaxHoleFillCost on this grid (refused before any work).
Result<Heightfield> holeFill(const Heightfield& terrain, const HoleFillParams& p);
// Pixel visits of `generations` generations of three quilts each on a width x height grid (blocks
// over the hole's rectangle clipped to the grid x candidates x patch pixels, twice with a guide,
// plus the grid per generation), in O(1).
uint64_t holeFillCost(const HoleFillParams& p, int width, int height, int generations);
// That cost against limits::kMaxHoleFillCost; the error names `choices` and the cost.
Status checkHoleFillCost(const HoleFillParams& p, int width, int height, int generations);

// ---- Perspective canvas (s4.1) ----

struct Point2 {
    double x = 0, y = 0;
};
struct Line2 {
    Point2 a, b;  // two distinct points on the line
};
// Plane projective map, row-major 3x3.
struct Homography {
    std::array<double, 9> m{1, 0, 0, 0, 1, 0, 0, 0, 1};
    Point2 apply(Point2 p) const;
    Homography inverse() const;
};
// The map sending from[i] to to[i] (DLT on four correspondences). Error when three points are collinear.
Result<Homography> homographyFromPoints(const std::array<Point2, 4>& from, const std::array<Point2, 4>& to);
// Intersection of two lines; error when parallel.
Result<Point2> intersectLines(const Line2& a, const Line2& b);

// The artist's perspective set-up over a reference image (image pixels, v grows downward): the
// horizon line, and the four outer lines of the ground grid drawn over the image. The grid is the
// ground quadrilateral `ground` (terrain pixels, order near-left, near-right, far-right, far-left).
struct PerspectiveCanvas {
    int image_width = 0, image_height = 0;
    Line2 horizon;
    Line2 grid_left, grid_right, grid_near, grid_far;
    std::array<Point2, 4> ground{};
    double camera_height_m = 100.0;  // eye height above the ground plane; sets the elevation scale
};
struct PerspectiveMapping {
    Homography ground_to_image;
    Homography image_to_ground;
    std::array<Point2, 4> image_quad;  // grid corners in the image, same order as ground
    Line2 horizon;
};
// Corners = intersections of the grid lines; homography between that quad and `ground`. Errors name
// the canvas field (parallel grid lines, corners beyond the horizon, degenerate quad).
Result<PerspectiveMapping> solvePerspective(const PerspectiveCanvas& canvas);
// Where the mapping puts the horizon (image of the ground's line at infinity); for checking the
// artist's horizon against the grid.
Line2 vanishingLine(const Homography& ground_to_image);

// A silhouette stroke drawn over the reference image: the ridge's outline against the sky.
struct SilhouetteStroke {
    std::vector<Point2> points;   // image pixels, >= 2
    std::optional<double> base_v; // image row where the feature stands on the ground; default: the
                                  // stroke's lowest point
    double width_px = 16.0;       // ridge cross-section (terrain pixels)
};
// Each stroke becomes a ridge: the foot (u, base_v) of every stroke point maps to the ground through
// the homography, and its elevation follows single-view metrology, camera_height *
// (base_v - v) / (base_v - v_horizon(u)): the same drawn height means more metres the farther
// (closer to the horizon) the foot is (s4.1: elevation from depth on the ground plane).
Result<std::vector<RidgeParams>> strokesToRidges(const PerspectiveCanvas& canvas,
                                                 const std::vector<SilhouetteStroke>& strokes);

}  // namespace terrasynth
