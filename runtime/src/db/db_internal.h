// Private building blocks of the exemplar database (runtime/include/terrasynth/database.h).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "terrasynth/database.h"

namespace terrasynth::db {

// Number of PCA modes kept per pixel for PatchMatch distances (more than the 4 stored, so the
// similarity table sees finer neighbourhood detail than synthesis does).
constexpr int kMatchModes = 8;
constexpr int kNeighbourhoodSide = 5;
constexpr int kNeighbourhoodSize = kNeighbourhoodSide * kNeighbourhoodSide;

// Gaussian pyramid E^0..E^levels (paper s4: a pyramid, not a stack). Level i+1 is level i filtered
// with the binomial [1 3 3 1]/8 and decimated by two, floor(size/2) per side, so level-(i+1) pixel p
// sits at level-i coordinate 2p + 0.5 (pixel centres at integers).
std::vector<Heightfield> buildGaussianPyramid(const Heightfield& base, int levels);

// Per pixel of one exemplar level: weighted mean height of the 5x5 neighbourhood and the
// sqrt(weight)-scaled deviations from it (so squared distances are Gaussian-weighted).
struct NeighbourhoodFeatures {
    int width = 0, height = 0;
    std::vector<float> mean;        // width*height
    std::vector<float> deviations;  // width*height*25
};
// Rows are split over `threads` (0 = hardware); the result does not depend on it.
NeighbourhoodFeatures extractNeighbourhoods(const Heightfield& level, int threads = 0);
// The Gaussian weights of the 5x5 window (sum 1), row-major.
const std::array<float, kNeighbourhoodSize>& neighbourhoodWeights();

// Principal axes of the deviation vectors of all exemplars at one level, strongest first.
struct PcaBasis {
    std::array<std::array<float, kNeighbourhoodSize>, kMatchModes> axes{};
    std::array<double, kMatchModes> variance{};
};
PcaBasis fitPca(const std::vector<const NeighbourhoodFeatures*>& exemplars);
// Projects every pixel's deviations onto the first `modes` axes: width*height*modes floats.
std::vector<float> projectFeatures(const NeighbourhoodFeatures& features, const PcaBasis& basis, int modes,
                                   int threads = 0);

// Shelf packing of exemplar rectangles with kAtlasGutter pixels around each.
struct AtlasLayout {
    int width = 0, height = 0;
    std::vector<AtlasRect> rects;
};
AtlasLayout packAtlas(const std::vector<std::pair<int, int>>& sizes);

// PatchMatch (Barnes et al. 2009) over per-pixel feature vectors of an atlas: for each pixel of an
// exemplar, the most similar *eligible* pixel: eligible[q] true, and q in another exemplar or at
// least kSimilarSeparation away (Chebyshev). Initialised from random-projection trees (and
// `initial` when given); rows are swept in fixed bands that read each other's previous-iteration
// field, so the result is independent of the thread count. dims must be 1..kMatchModes.
struct PatchMatchInput {
    int width = 0, height = 0, dims = 0;
    const float* features = nullptr;      // width*height*dims
    const uint8_t* exemplar = nullptr;    // per pixel, kNoExemplar outside exemplars
    const uint8_t* eligible = nullptr;    // per pixel: may be a match
    uint32_t salt = 0;                    // varies the random choices (e.g. by level)
    // Optional starting guess per pixel (e.g. the coarser level's matches carried down by
    // upsampleMatches); entries that are not acceptable matches, or UINT32_MAX, are ignored.
    const uint32_t* initial = nullptr;
};
std::vector<uint32_t> patchMatch(const PatchMatchInput& input, int iterations, int threads);
// The matches of a coarser level carried down to the next finer one (coarse-to-fine
// initialisation): fine pixel (x, y) of exemplar e looks up coarse pixel (x/2, y/2) of e, whose match
// (u, v) in exemplar e' becomes (2u + x%2, 2v + y%2) in e' at the fine level. UINT32_MAX where
// there is no guess.
std::vector<uint32_t> upsampleMatches(const DatabaseLevel& coarse, const std::vector<AtlasRect>& fine_rects,
                                      int fine_width, int fine_height);
// Exhaustive search with the same rules, for tests.
std::vector<uint32_t> bruteForceMatch(const PatchMatchInput& input);
float featureDistance(const PatchMatchInput& input, uint32_t a, uint32_t b);

// NoData voids through resampling and the pyramid (docs/formats.md, "Voids"). Masks are width*height
// bytes, 1 = void; an empty mask means no voids.
// The voids of `nodata` (at `original`'s size and spacing) once the exemplar is resampled to
// `meters_per_pixel` (resampleToSpacing): a pixel is a void when more than a thousandth of its
// resampled height comes from void samples.
std::vector<uint8_t> resampleVoids(const std::vector<uint8_t>& nodata, const Heightfield& original,
                                   double meters_per_pixel);
// The voids of pyramid level i+1 (coarse_w x coarse_h) from level i's: a pixel whose [1 3 3 1]
// filter reads any level-i void (its height then holds fill) is a void.
std::vector<uint8_t> coarserVoids(const std::vector<uint8_t>& fine, int fine_w, int fine_h, int coarse_w, int coarse_h);
// The voids grown by kInteriorMargin pixels (Chebyshev): what the database treats like the
// exemplar's own edge, so no candidate's neighbourhood reads a void.
std::vector<uint8_t> voidMargins(const std::vector<uint8_t>& voids, int width, int height);

// Runs body(row_begin, row_end) over [0, rows) on `threads` threads (0 = hardware).
void parallelRows(int rows, int threads, const std::function<void(int, int)>& body);

}  // namespace terrasynth::db
