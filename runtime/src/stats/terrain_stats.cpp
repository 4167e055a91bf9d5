// computeTerrainStats: every metric of terrain_stats.h on one heightfield.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "stats/binning.h"
#include "stats/flow_routing.h"
#include "terrasynth/terrain_stats.h"

namespace terrasynth {
namespace {

constexpr int kMinSide = 32;
constexpr int kReliefWindow = 9;

// Finite values of a map over the pixels at least `margin` away from every border.
std::vector<double> interiorSamples(const std::vector<float>& map, int w, int h, int margin) {
    std::vector<double> out;
    out.reserve(static_cast<size_t>(std::max(0, w - 2 * margin)) * std::max(0, h - 2 * margin));
    for (int y = margin; y < h - margin; ++y)
        for (int x = margin; x < w - margin; ++x) {
            const float v = map[static_cast<size_t>(y) * w + x];
            if (std::isfinite(v)) out.push_back(v);
        }
    return out;
}

// tau of P(A >= a) ~ a^-tau between 10 cells and 1% of the field (the range where the power law of
// river networks holds before the finite field truncates it). Areas are whole cell counts, so a
// counting pass replaces a sort.
double exceedanceExponent(const std::vector<double>& area, double cell_area) {
    const size_t n = area.size();
    const double a_lo = 10.0, a_hi = 0.01 * static_cast<double>(n);
    if (a_hi < 10.0 * a_lo) return std::numeric_limits<double>::quiet_NaN();
    std::vector<size_t> at_least(n + 2, 0);
    for (double a : area) ++at_least[std::min(n, static_cast<size_t>(std::lround(a / cell_area)))];
    for (size_t c = n; c-- > 0;) at_least[c] += at_least[c + 1];
    double k = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (double la = std::log10(a_lo); la <= std::log10(a_hi) + 1e-9; la += 0.1) {
        const size_t cells = static_cast<size_t>(std::ceil(std::pow(10.0, la)));
        const double p = static_cast<double>(at_least[cells]) / static_cast<double>(n);
        if (p <= 0.0) continue;
        const double x = std::log10(static_cast<double>(cells)), y = std::log10(p);
        k += 1;
        sx += x;
        sy += y;
        sxx += x * x;
        sxy += x * y;
    }
    const double vx = sxx - sx * sx / k;
    if (k < 3 || !(vx > 0.0)) return std::numeric_limits<double>::quiet_NaN();
    return -(sxy - sx * sy / k) / vx;
}

double shareOf(const std::vector<uint8_t>& mask, int w, int h, int margin) {
    size_t hits = 0, total = 0;
    for (int y = margin; y < h - margin; ++y)
        for (int x = margin; x < w - margin; ++x) {
            hits += mask[static_cast<size_t>(y) * w + x] != 0;
            ++total;
        }
    return total ? static_cast<double>(hits) / static_cast<double>(total) : 0.0;
}

double depressionShare(const Heightfield& field, const std::vector<double>& filled) {
    size_t raised = 0;
    for (size_t i = 0; i < field.size(); ++i) raised += stats::inDepression(field.heights[i], filled[i]);
    return static_cast<double>(raised) / static_cast<double>(field.size());
}

std::array<double, kLandformCount> landformShares(const Heightfield& field) {
    const std::vector<uint8_t> classes = classifyLandforms(field);
    std::array<double, kLandformCount> share{};
    size_t total = 0;
    for (int y = 1; y < field.height - 1; ++y)
        for (int x = 1; x < field.width - 1; ++x) {
            share[classes[static_cast<size_t>(y) * field.width + x]] += 1.0;
            ++total;
        }
    for (double& s : share) s /= static_cast<double>(total);
    return share;
}

}  // namespace

Result<TerrainStats> computeTerrainStats(const Heightfield& field) {
    if (field.empty()) return Status::error("terrain stats: empty heightfield");
    if (Status valid = validateHeightfield(field); !valid) return valid.withContext("terrain stats");
    if (field.width < kMinSide || field.height < kMinSide)
        return Status::error("terrain stats: need at least 32x32 samples, got " + std::to_string(field.width) + "x" +
                             std::to_string(field.height));
    const int w = field.width, h = field.height;
    TerrainStats s;
    s.width = w;
    s.height = h;
    s.meters_per_pixel_x = field.meters_per_pixel_x;
    s.meters_per_pixel_y = field.meters_per_pixel_y;

    using stats::BinKind;
    std::vector<double> samples = interiorSamples(slopeDegrees(field), w, h, 1);
    s.slope_deg = stats::describe(samples, BinKind::SlopeDeg);
    {
        const CurvatureMaps k = curvatures(field);
        samples = interiorSamples(k.profile, w, h, 1);
        s.profile_curvature = stats::describe(samples, BinKind::Curvature);
        samples = interiorSamples(k.plan, w, h, 1);
        s.plan_curvature = stats::describe(samples, BinKind::Curvature);
    }
    samples = interiorSamples(localRelief(field, kReliefWindow), w, h, kReliefWindow / 2);
    s.local_relief_m = stats::describe(samples, BinKind::ReliefM);

    {
        stats::FlowRouting flow = stats::routeFlow(field);
        s.depression_share = depressionShare(field, flow.filled);
        s.drainage_exceedance_exponent =
            exceedanceExponent(flow.area, field.meters_per_pixel_x * field.meters_per_pixel_y);
        s.drainage_area_m2 = stats::describe(flow.area, BinKind::DrainageAreaM2);
    }
    s.pit_share = shareOf(pitMask(field), w, h, 1);
    s.landform_share = landformShares(field);

    auto spectrum = powerSpectrum(field);
    if (!spectrum) return spectrum.status().withContext("terrain stats");
    s.spectrum = std::move(spectrum.value());
    return s;
}

}  // namespace terrasynth
