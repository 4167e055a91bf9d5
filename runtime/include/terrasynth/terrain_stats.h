// terrasynth/terrain_stats.h: geomorphological realism statistics of a heightfield, distances between
// two terrains' statistics, and the "reference spread" that says how far apart pieces of real
// exemplars are, so a synthesized terrain can be judged against real variation.
//
// docs/realism.md explains each metric, its units and bins, and how to read distances.
//
// Units: heights and lengths in metres, areas in m^2, slope in degrees, curvature in 1/m, using the
// field's meters_per_pixel_x / meters_per_pixel_y (anisotropic spacing is honoured everywhere).
// Distributions are only comparable between terrains at the same spacing: resample first
// (resampleToSpacing in heightfield.h). Several metrics also depend on extent (drainage area,
// spectral fit range), so compare pieces of similar size.
//
// Threading: every function is re-entrant and uses only its arguments; call them from any thread.
// None of them spawns threads. Cost: O(n log n) in the pixel count; a 1024^2 field takes well under
// a second on one core.
//
// Typical use in a synthesis test:
//   auto spread = referenceSpread(exemplar_fields, 256);              // Result<ReferenceSpread>
//   auto d = distanceToReference(synthesized, *spread);               // Result<StatsDistance>
//   SpreadVerdict v = judgeAgainstSpread(*d, *spread);                // v.within, v.ratio[...]
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "terrasynth/heightfield.h"
#include "terrasynth/status.h"

namespace terrasynth {

// ---------------------------------------------------------------------------------------------
// Distributions

// A histogram with fixed bins (the bins of each metric never depend on the data, so histograms of
// different terrains line up bin for bin). Values outside the edges are counted in the end bins.
struct Histogram {
    std::vector<double> edges;  // bins+1 strictly increasing edges, in the metric's units
    std::vector<double> mass;   // fraction of the samples in each bin; sums to 1 (all 0 when empty)
    // Where each bin sits when measuring Wasserstein distance: the bin centre in the metric's units,
    // or log10 of the geometric centre for log-binned metrics (then distances are in decades).
    std::vector<double> position;
    bool log_distance = false;  // true: Wasserstein-1 is measured in log10 units (drainage area)
};

// A metric's sample distribution: the histogram plus exact summary figures of the samples.
// When there are no samples every figure is 0 and the histogram mass is all 0.
struct Distribution {
    Histogram histogram;
    size_t samples = 0;
    double mean = 0.0, stddev = 0.0;
    double min = 0.0, p10 = 0.0, median = 0.0, p90 = 0.0, p99 = 0.0, max = 0.0;
};

// Wasserstein-1 (earth mover's) distance between two histograms with the same bins: the integral of
// |CDF_a - CDF_b| over the bin positions, in the metric's units (log10 units when log_distance).
// Requires identical edges (programmer error otherwise). 0 when either histogram is empty.
double wasserstein1(const Histogram& a, const Histogram& b);
// Kolmogorov-Smirnov statistic between two histograms with the same bins: max |CDF_a - CDF_b| over
// the bin edges, in [0, 1]. 0 when either histogram is empty.
double kolmogorovSmirnov(const Histogram& a, const Histogram& b);

// ---------------------------------------------------------------------------------------------
// Landform classes (docs/realism.md, "Landform classes"): a Pennock-like six-class scheme on slope,
// profile curvature and plan curvature.

enum class Landform : uint8_t {
    Flat = 0,       // slope below flat_slope_deg
    PeakRidge,      // contour-convex (divergent) and not profile-concave: crests, spurs, summits
    ValleyChannel,  // contour-concave (convergent) and not profile-convex: channels, hollows
    Shoulder,       // profile-convex slope that is neither ridge nor valley (slope steepening downhill)
    Footslope,      // profile-concave slope that is neither ridge nor valley (slope easing downhill)
    Backslope,      // planar slope: curvatures below the threshold
};
constexpr int kLandformCount = 6;
const char* landformName(Landform landform);  // "flat", "peak/ridge", ... (static strings)

struct LandformThresholds {
    double flat_slope_deg = 2.0;
    // A curvature counts as convex/concave when |k| * spacing exceeds this, i.e. when the gradient
    // changes by more than this (in rise/run) from one pixel to the next. Scaling with the spacing
    // keeps the class shares of one landscape stable across DEM resolutions.
    double curvature_gradient_change = 0.05;
};

// ---------------------------------------------------------------------------------------------
// Per-pixel building blocks. Each returns a width*height row-major map for a non-empty field.
// Border pixels (which lack a full neighbourhood) use clamped neighbours and are approximations;
// computeTerrainStats leaves them out of the distributions. Preconditions (programmer errors):
// field not empty and heights.size() == width*height.

// Slope in degrees [0, 90) from central differences, honouring the x/y spacing.
std::vector<float> slopeDegrees(const Heightfield& field);

// Profile and plan curvature in 1/m (Zevenbergen & Thorne 1987: second derivative of the surface
// along the gradient direction and along the contour direction). Sign convention: positive =
// convex (surface bulges up: crests, shoulders), negative = concave (channels, footslopes).
// Pixels whose gradient is below 1e-4 have no direction; both curvatures are NaN there.
struct CurvatureMaps {
    std::vector<float> profile;
    std::vector<float> plan;
};
CurvatureMaps curvatures(const Heightfield& field);

// Local relief in metres: max - min over a window x window neighbourhood (clipped at the border).
// window must be odd and >= 3.
std::vector<float> localRelief(const Heightfield& field, int window = 9);

// Priority-Flood depression filling (Barnes, Lehman & Mulla 2014). Every cell is raised to the
// lowest level from which water can leave through the field's border. With epsilon = false flats
// remain flat (Barnes Alg. 2); with epsilon = true each raised cell sits one float step above the
// cell it drains to (Priority-Flood+epsilon, Alg. 3), so every interior cell has a strictly lower
// neighbour and D8 flow is defined everywhere. Idempotent. O(n log n).
Heightfield fillDepressions(const Heightfield& field, bool epsilon);

// D8 drainage area in m^2 (each cell's own area plus the area of every cell draining through it),
// computed on the Priority-Flood+epsilon filled surface so flow crosses pits and flats. Each cell
// drains to the neighbour with the steepest descent (diagonals at their true distance); border
// cells drain off the field (the terrain beyond is unknown), so no flow runs along the border.
std::vector<double> drainageArea(const Heightfield& field);

// 1 for interior pixels strictly lower than all 8 neighbours (closed pits), 0 elsewhere.
std::vector<uint8_t> pitMask(const Heightfield& field);

// Per-pixel landform class (values of Landform) from the maps above.
std::vector<uint8_t> classifyLandforms(const Heightfield& field,
                                       const LandformThresholds& thresholds = LandformThresholds());

// Radially averaged power spectrum and its log-log slope (docs/realism.md, "Spectral slope").
// Welch estimate: square tiles of T = min(512, largest power of two <= min(width, height)) pixels,
// 50% overlap; each tile has its best-fit plane removed and a 2D Hann window applied. Power is
// averaged over annuli of radial frequency (10 log bins per decade), and a least-squares line is
// fitted to log10(power) vs log10(frequency) for frequencies between 4 cycles per tile and 1/4 cycle
// per pixel. Convention: slope_2d is the slope of the 2D power spectral density (mean power per
// annulus); for fractional Brownian surfaces slope_2d = -(2H + 2). slope_1d = slope_2d + 1 is the
// equivalent slope of 1D profile spectra, -(2H + 1); real terrain mostly gives slope_1d in -2 .. -3.
struct Spectrum {
    std::vector<double> frequency_per_m;  // geometric mean radial frequency of each annulus, cycles/m
    std::vector<double> power;            // mean power spectral density in each annulus, m^2/(cycle/m)^2
    double slope_2d = 0.0;
    double slope_1d = 0.0;
    double hurst = 0.0;                   // H = (-slope_2d - 2) / 2 (only meaningful for 0 < H < 1)
    double fit_r2 = 0.0;                  // coefficient of determination of the fit, 0..1
    int tile_size = 0;
};
// Requires width, height >= 32 (error otherwise).
Result<Spectrum> powerSpectrum(const Heightfield& field);

// ---------------------------------------------------------------------------------------------
// Whole-terrain statistics

struct TerrainStats {
    int width = 0, height = 0;
    double meters_per_pixel_x = 0.0, meters_per_pixel_y = 0.0;

    // Distributions over interior pixels (1 pixel border left out; 4 for the 9x9 relief window).
    // Bins: docs/realism.md, "Bins".
    Distribution slope_deg;            // degrees
    Distribution profile_curvature;    // 1/m, positive convex; pixels without gradient left out
    Distribution plan_curvature;       // 1/m, positive convex (divergent)
    Distribution local_relief_m;       // metres, 9x9 window
    Distribution drainage_area_m2;     // m^2, log bins, every pixel
    // tau in P(A >= a) ~ a^-tau, fitted between 10 cells and 1% of the field's area; river networks
    // give about 0.4-0.55 (Rodriguez-Iturbe & Rinaldo 1997). NaN for fields under 10000 pixels.
    double drainage_exceedance_exponent = 0.0;
    double pit_share = 0.0;            // strict local minima / interior pixels, before filling
    double depression_share = 0.0;     // pixels in depressions (raised by Priority-Flood) / all pixels
    std::array<double, kLandformCount> landform_share{};  // over interior pixels, sums to 1
    Spectrum spectrum;
};

// Computes every metric. Errors (message names the problem): empty field, size mismatch,
// non-finite heights or spacing, or a side shorter than 32 pixels.
Result<TerrainStats> computeTerrainStats(const Heightfield& field);

// ---------------------------------------------------------------------------------------------
// Distances between two terrains

enum class Metric : int {
    Slope = 0,             // W1 in degrees
    ProfileCurvature,      // W1 in 1/m
    PlanCurvature,         // W1 in 1/m
    LocalRelief,           // W1 in metres
    DrainageArea,          // W1 in decades (log10 m^2)
    DrainageExponent,      // |difference| of tau
    PitShare,              // |difference| of the share (0..1)
    DepressionShare,       // |difference| of the share (0..1)
    Landforms,             // total variation distance of the class shares (0..1)
    SpectralSlope,         // |difference| of slope_1d (equal to that of slope_2d)
};
constexpr int kMetricCount = 10;
const char* metricName(Metric metric);  // "slope", "profile_curvature", ... (static strings)
const char* metricUnit(Metric metric);  // "deg", "1/m", "m", "decades", "" (static strings)

struct MetricDistance {
    // Wasserstein-1 for distributions (units above); |a - b| for scalars; total variation for the
    // landform shares.
    double value = 0.0;
    // Kolmogorov-Smirnov for distributions (0..1); for scalars and landforms the same as value.
    double ks = 0.0;
};

struct StatsDistance {
    std::array<MetricDistance, kMetricCount> metric{};
    MetricDistance& operator[](Metric m) { return metric[static_cast<int>(m)]; }
    const MetricDistance& operator[](Metric m) const { return metric[static_cast<int>(m)]; }
};

// Per-metric distances between two terrains' statistics. Precondition (programmer error): both were
// computed at the same spacing (within 1%); resample first otherwise.
StatsDistance compareStats(const TerrainStats& a, const TerrainStats& b);

// ---------------------------------------------------------------------------------------------
// Reference spread: how far apart pieces of real exemplars are from each other.

// Non-overlapping piece_size x piece_size tiles of the field, centred (the remainder is split
// evenly between the borders), row-major. Empty when the field is smaller than one piece.
std::vector<Heightfield> cutIntoPieces(const Heightfield& field, int piece_size);

struct ReferenceSpread {
    int piece_size = 0;
    double meters_per_pixel = 0.0;   // all pieces were resampled to this spacing
    int pieces = 0;
    int pairs = 0;                   // pieces*(pieces-1)/2 distances were measured
    StatsDistance median;            // per metric, over all pairs
    StatsDistance max;               // per metric, over all pairs
    std::vector<TerrainStats> piece_stats;
};

// Resamples every exemplar to meters_per_pixel (0: the first exemplar's x spacing), cuts each into
// pieces of piece_size (>= 32), computes their statistics and the pairwise distances between all
// pieces (within and across exemplars). Errors: invalid exemplar heights, or fewer than 2 pieces.
Result<ReferenceSpread> referenceSpread(const std::vector<Heightfield>& exemplars, int piece_size,
                                        double meters_per_pixel = 0.0);

// Distance of a candidate terrain to the reference: the candidate is resampled to the reference
// spacing and cut into square pieces of the reference piece size (or of the candidate's shorter
// side when that is smaller, down to 32); per metric, the median over all (candidate piece,
// reference piece) pairs. Comparable to ReferenceSpread::median / max.
Result<StatsDistance> distanceToReference(const Heightfield& candidate, const ReferenceSpread& reference);

struct SpreadVerdict {
    // distance / reference max per metric (0 when both are 0, +inf when only the max is 0, NaN when
    // either is NaN).
    std::array<double, kMetricCount> ratio{};
    bool within = true;                 // no metric is outside
    // Metrics whose ratio exceeds slack or whose distance is NaN while the reference's max is not.
    // Metrics the reference itself leaves undefined (NaN max) are not judged.
    std::vector<Metric> outside;
};
// Judges distances (from distanceToReference or compareStats) against the reference's largest
// piece-to-piece distance, metric by metric, using MetricDistance::value.
SpreadVerdict judgeAgainstSpread(const StatsDistance& distance, const ReferenceSpread& reference,
                                 double slack = 1.0);

}  // namespace terrasynth
