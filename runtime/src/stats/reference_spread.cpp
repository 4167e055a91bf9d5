// The reference spread: distances between pieces of real exemplars, the yardstick a synthesized
// terrain's distance to those exemplars is read against (docs/realism.md, "Reading distances").
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "terrasynth/terrain_stats.h"

namespace terrasynth {
namespace {

constexpr int kMinPiece = 32;

// Per-metric median and max of a list of distances; NaN entries (metrics undefined on some piece)
// are left out.
void summarise(const std::vector<StatsDistance>& all, StatsDistance* median, StatsDistance* max) {
    for (int m = 0; m < kMetricCount; ++m) {
        for (int field = 0; field < 2; ++field) {
            std::vector<double> v;
            for (const StatsDistance& d : all) {
                const double x = field == 0 ? d.metric[m].value : d.metric[m].ks;
                if (std::isfinite(x)) v.push_back(x);
            }
            double med = std::numeric_limits<double>::quiet_NaN(), mx = med;
            if (!v.empty()) {
                std::sort(v.begin(), v.end());
                const size_t k = v.size();
                med = k % 2 ? v[k / 2] : 0.5 * (v[k / 2 - 1] + v[k / 2]);
                mx = v.back();
            }
            (field == 0 ? median->metric[m].value : median->metric[m].ks) = med;
            (field == 0 ? max->metric[m].value : max->metric[m].ks) = mx;
        }
    }
}

Result<std::vector<TerrainStats>> statsOfPieces(const Heightfield& field, int piece_size, const std::string& what) {
    std::vector<TerrainStats> out;
    for (const Heightfield& piece : cutIntoPieces(field, piece_size)) {
        auto s = computeTerrainStats(piece);
        if (!s) return s.status().withContext(what);
        out.push_back(std::move(s.value()));
    }
    return out;
}

}  // namespace

std::vector<Heightfield> cutIntoPieces(const Heightfield& field, int piece_size) {
    TERRASYNTH_REQUIRE(piece_size > 0, "piece size must be positive");
    std::vector<Heightfield> pieces;
    const int nx = field.width / piece_size, ny = field.height / piece_size;
    const int x_off = (field.width - nx * piece_size) / 2, y_off = (field.height - ny * piece_size) / 2;
    for (int py = 0; py < ny; ++py)
        for (int px = 0; px < nx; ++px) {
            Heightfield piece(piece_size, piece_size, field.meters_per_pixel_x);
            piece.meters_per_pixel_y = field.meters_per_pixel_y;
            for (int y = 0; y < piece_size; ++y) {
                const float* row = &field.heights[static_cast<size_t>(y_off + py * piece_size + y) * field.width +
                                                  x_off + px * piece_size];
                std::copy(row, row + piece_size, &piece.heights[static_cast<size_t>(y) * piece_size]);
            }
            pieces.push_back(std::move(piece));
        }
    return pieces;
}

Result<ReferenceSpread> referenceSpread(const std::vector<Heightfield>& exemplars, int piece_size,
                                        double meters_per_pixel) {
    if (piece_size < kMinPiece)
        return Status::error("reference spread: piece size " + std::to_string(piece_size) + " is below 32");
    if (exemplars.empty()) return Status::error("reference spread: no exemplars");
    ReferenceSpread ref;
    ref.piece_size = piece_size;
    ref.meters_per_pixel = meters_per_pixel > 0.0 ? meters_per_pixel : exemplars.front().meters_per_pixel_x;
    for (size_t e = 0; e < exemplars.size(); ++e) {
        const std::string what = "reference spread: exemplar " + std::to_string(e);
        if (Status valid = validateHeightfield(exemplars[e]); !valid) return valid.withContext(what);
        auto pieces = statsOfPieces(resampleToSpacing(exemplars[e], ref.meters_per_pixel), piece_size, what);
        if (!pieces) return pieces.status();
        for (TerrainStats& s : pieces.value()) ref.piece_stats.push_back(std::move(s));
    }
    ref.pieces = static_cast<int>(ref.piece_stats.size());
    if (ref.pieces < 2)
        return Status::error("reference spread: the exemplars give " + std::to_string(ref.pieces) +
                             " piece(s) of " + std::to_string(piece_size) + "^2 at " +
                             std::to_string(ref.meters_per_pixel) + " m/pixel; need at least 2");
    std::vector<StatsDistance> distances;
    for (int i = 0; i < ref.pieces; ++i)
        for (int j = i + 1; j < ref.pieces; ++j)
            distances.push_back(compareStats(ref.piece_stats[i], ref.piece_stats[j]));
    ref.pairs = static_cast<int>(distances.size());
    summarise(distances, &ref.median, &ref.max);
    return ref;
}

Result<StatsDistance> distanceToReference(const Heightfield& candidate, const ReferenceSpread& reference) {
    TERRASYNTH_REQUIRE(reference.pieces >= 1 && reference.meters_per_pixel > 0.0,
                       "distanceToReference needs a reference from referenceSpread");
    if (Status valid = validateHeightfield(candidate); !valid) return valid.withContext("candidate terrain");
    const Heightfield resampled = resampleToSpacing(candidate, reference.meters_per_pixel);
    const int piece = std::min({reference.piece_size, resampled.width, resampled.height});
    if (piece < kMinPiece)
        return Status::error("candidate terrain: " + std::to_string(resampled.width) + "x" +
                             std::to_string(resampled.height) + " at the reference spacing is below 32x32");
    auto pieces = statsOfPieces(resampled, piece, "candidate terrain");
    if (!pieces) return pieces.status();
    std::vector<StatsDistance> distances;
    for (const TerrainStats& c : pieces.value())
        for (const TerrainStats& r : reference.piece_stats) distances.push_back(compareStats(c, r));
    StatsDistance median, max;
    summarise(distances, &median, &max);
    return median;
}

SpreadVerdict judgeAgainstSpread(const StatsDistance& distance, const ReferenceSpread& reference, double slack) {
    SpreadVerdict v;
    for (int m = 0; m < kMetricCount; ++m) {
        const double d = distance.metric[m].value, limit = reference.max.metric[m].value;
        double r;
        if (std::isnan(d) || std::isnan(limit)) r = std::numeric_limits<double>::quiet_NaN();
        else if (limit > 0.0) r = d / limit;
        else r = d > 0.0 ? std::numeric_limits<double>::infinity() : 0.0;
        v.ratio[m] = r;
        // A metric the reference cannot define (e.g. the drainage exponent on pieces under 100^2) is not
        // judged; one the candidate alone lacks is outside, since it cannot vouch for realism.
        if (std::isnan(limit)) continue;
        if (!(r <= slack)) {
            v.within = false;
            v.outside.push_back(static_cast<Metric>(m));
        }
    }
    return v;
}

}  // namespace terrasynth
