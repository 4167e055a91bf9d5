// terrasynth/database.h: the exemplar database of Gain, Merry & Marais 2015, section 4.
//
// Per pyramid level i = 0..L every exemplar is stored in one atlas per level (all exemplars side by
// side, 4-pixel gutters between them) holding per pixel:
//   height      E^i, metres (float)                                        4 bytes
//   appearance  A^i, 4 PCA modes of the Gaussian-weighted 5x5 neighbourhood, 16-bit each.
//               Mode 0 is replaced by the weighted mean height (paper s4); modes 1..3 are
//               the principal components of the neighbourhood *minus* that mean, so adding a
//               height offset h changes mode 0 only (the a = (1 0 0 0)^T of eq. 4-5).     8 bytes
//   similar     C^i_2, the most similar neighbourhood found by PatchMatch, as an atlas pixel
//               index; at least kSimilarSeparation pixels from p (or in another exemplar), never
//               within kInteriorMargin of an exemplar edge or of a NoData void. C^i_1(p) = p
//               itself, as in Lefebvre & Hoppe 2005, so it is not stored.             4 bytes
//   type        T^i, terrain type (majority of the 2^i x 2^i block of T^0); kNoType where there
//               is nothing to copy: in gutters, and on an exemplar's NoData voids and the
//               kInteriorMargin pixels around them (at coarser levels, wherever the pyramid
//               filter read a void). Synthesis never copies a kNoType pixel: it is no
//               match, no identity candidate and no type seed.                        1 byte
//   exemplar    exemplar index, kNoExemplar in the padding                              1 byte
//   closed      1 where the pixel lies in a closed depression of its own exemplar at this level
//               (Priority-Flood raises it), so drainage keeps real basins               1 byte
// = 19 bytes per pixel per level, about 25 per base pixel with the pyramid (paper: 42.7).
//
// Building is deterministic: the same inputs and options give the same bytes, whatever the thread
// count. A database is immutable after building and safe to share between threads.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "terrasynth/heightfield_io.h"
#include "terrasynth/status.h"

namespace terrasynth {

constexpr uint8_t kNoType = 255;
constexpr uint8_t kNoExemplar = 255;
constexpr int kMaxExemplars = 254;
constexpr int kMaxTypes = 254;
constexpr int kAtlasGutter = 4;        // pixels between exemplars in an atlas
constexpr int kInteriorMargin = 2;     // candidates stay this far from exemplar edges
constexpr int kSimilarSeparation = 4;  // Chebyshev distance between C_1(p) = p and C_2(p)
constexpr int kTypeSeedCount = 64;     // random coordinates kept per type and level (paper s5.2)

struct AtlasRect {
    int x = 0, y = 0, width = 0, height = 0;  // the exemplar's pixels inside the atlas
};

struct DatabaseLevel {
    int width = 0, height = 0;            // atlas size in pixels
    std::vector<float> height_m;          // E^i
    std::vector<uint16_t> appearance;     // A^i, 4 per pixel, quantised
    float appearance_offset[4] = {0, 0, 0, 0};  // value_m = offset + scale * quantised
    float appearance_scale[4] = {1, 1, 1, 1};
    std::vector<uint32_t> similar;        // C^i_2 as atlas index y*width+x
    std::vector<uint8_t> type;            // T^i
    std::vector<uint8_t> exemplar;        // exemplar index per pixel
    // 1 where the exemplar pixel is in a closed depression of its exemplar at this level (raised by
    // Priority-Flood without epsilon, the exemplar's edge draining out), else 0; 0 in gutters.
    // Drainage (synthesizer.h) leaves pits copied from such pixels alone: dune hollows, karst,
    // crater lakes and salars are real.
    std::vector<uint8_t> closed;
    std::vector<AtlasRect> rects;         // per exemplar
    // Per type: kTypeSeedCount atlas indices of interior pixels of that type, drawn at random
    // (deterministically) for type seeding (s5.2) and for initialising the coarsest level.
    std::vector<std::vector<uint32_t>> type_seeds;

    size_t pixelCount() const { return static_cast<size_t>(width) * height; }
    size_t memoryBytes() const;
};

struct ExemplarDatabase {
    static constexpr uint32_t kFormatVersion = 2;  // 2: DatabaseLevel::closed
    double meters_per_pixel = 0.0;             // spacing of level 0; level i has 2^i times this
    std::vector<ExemplarInfo> exemplars;
    std::vector<int> exemplar_type;            // default type of each exemplar (its terrain_class)
    std::vector<std::string> type_names;       // index = type id
    std::vector<DatabaseLevel> levels;         // 0 = finest
    uint64_t input_digest = 0;                 // digest of the inputs and options it was built from

    int levelCount() const { return static_cast<int>(levels.size()); }
    // Sum over exemplars of their level-0 pixels (what "per base pixel" divides by).
    size_t basePixelCount() const;
    size_t memoryBytes() const;
    double bytesPerBasePixel() const { return static_cast<double>(memoryBytes()) / basePixelCount(); }
};

struct DatabaseBuildOptions {
    int levels = 6;                    // L: pyramid E^0..E^L, so L+1 levels; 1..12
    double meters_per_pixel = 0.0;     // 0: the coarsest input spacing (never invents detail)
    int threads = 0;                   // 0: hardware concurrency
    int patchmatch_iterations = 6;
    // Called from the building thread with a stage name and progress in [0,1].
    std::function<void(const std::string& stage, double progress)> progress;
    // Called from the building thread for each exemplar with NoData voids (Exemplar::nodata), with
    // the share of its pixels that are voids, in (0, 1).
    std::function<void(const ExemplarInfo& exemplar, double void_share)> on_voids;
};

// Reads every input (files, or directories expanded with listExemplarFiles), resamples to a common
// spacing and builds the database. Errors name the offending file.
Result<std::shared_ptr<const ExemplarDatabase>> buildDatabase(const std::vector<std::string>& inputs,
                                                              const DatabaseBuildOptions& options);
// The same from exemplars already in memory.
Result<std::shared_ptr<const ExemplarDatabase>> buildDatabase(std::vector<Exemplar> exemplars,
                                                              const DatabaseBuildOptions& options);

// Digest of input file contents and the options that shape the database; a cache whose digest
// differs is stale.
Result<uint64_t> digestInputs(const std::vector<std::string>& inputs, const DatabaseBuildOptions& options);

// Versioned binary cache file (docs/formats.md). Saving is atomic. Loading verifies magic, version,
// section sizes and a checksum of the whole payload: a truncated, corrupt or foreign file is an error
// naming the file and the problem, never a partially trusted database.
Status saveDatabase(const ExemplarDatabase& db, const std::string& path);
Result<std::shared_ptr<const ExemplarDatabase>> loadDatabase(const std::string& path);

// Loads `cache_path` if it is valid and its digest matches the inputs; otherwise rebuilds and
// rewrites it. `rebuilt` (optional) tells which happened; `why` (optional) says why it rebuilt.
Result<std::shared_ptr<const ExemplarDatabase>> loadOrBuildDatabase(const std::vector<std::string>& inputs,
                                                                    const DatabaseBuildOptions& options,
                                                                    const std::string& cache_path,
                                                                    bool* rebuilt = nullptr,
                                                                    std::string* why = nullptr);

}  // namespace terrasynth
