// Per-metric distances between two terrains' statistics.
#include <cmath>

#include "terrasynth/terrain_stats.h"

namespace terrasynth {

const char* metricName(Metric metric) {
    switch (metric) {
        case Metric::Slope: return "slope";
        case Metric::ProfileCurvature: return "profile_curvature";
        case Metric::PlanCurvature: return "plan_curvature";
        case Metric::LocalRelief: return "local_relief";
        case Metric::DrainageArea: return "drainage_area";
        case Metric::DrainageExponent: return "drainage_exponent";
        case Metric::PitShare: return "pit_share";
        case Metric::DepressionShare: return "depression_share";
        case Metric::Landforms: return "landforms";
        case Metric::SpectralSlope: return "spectral_slope";
    }
    return "?";
}

const char* metricUnit(Metric metric) {
    switch (metric) {
        case Metric::Slope: return "deg";
        case Metric::ProfileCurvature:
        case Metric::PlanCurvature: return "1/m";
        case Metric::LocalRelief: return "m";
        case Metric::DrainageArea: return "decades";
        default: return "";
    }
}

namespace {

MetricDistance between(const Distribution& a, const Distribution& b) {
    return {wasserstein1(a.histogram, b.histogram), kolmogorovSmirnov(a.histogram, b.histogram)};
}

MetricDistance scalar(double a, double b) {
    const double d = std::fabs(a - b);
    return {d, d};
}

// Total variation: half the L1 distance of two discrete distributions, the largest difference in
// probability any set of classes can show.
MetricDistance totalVariation(const std::array<double, kLandformCount>& a,
                              const std::array<double, kLandformCount>& b) {
    double l1 = 0.0;
    for (int i = 0; i < kLandformCount; ++i) l1 += std::fabs(a[i] - b[i]);
    return {0.5 * l1, 0.5 * l1};
}

bool sameSpacing(double a, double b) { return std::fabs(a / b - 1.0) <= 0.01; }

}  // namespace

StatsDistance compareStats(const TerrainStats& a, const TerrainStats& b) {
    TERRASYNTH_REQUIRE(sameSpacing(a.meters_per_pixel_x, b.meters_per_pixel_x) &&
                           sameSpacing(a.meters_per_pixel_y, b.meters_per_pixel_y),
                       "compareStats needs both terrains at the same spacing; resampleToSpacing first");
    StatsDistance d;
    d[Metric::Slope] = between(a.slope_deg, b.slope_deg);
    d[Metric::ProfileCurvature] = between(a.profile_curvature, b.profile_curvature);
    d[Metric::PlanCurvature] = between(a.plan_curvature, b.plan_curvature);
    d[Metric::LocalRelief] = between(a.local_relief_m, b.local_relief_m);
    d[Metric::DrainageArea] = between(a.drainage_area_m2, b.drainage_area_m2);
    d[Metric::DrainageExponent] = scalar(a.drainage_exceedance_exponent, b.drainage_exceedance_exponent);
    d[Metric::PitShare] = scalar(a.pit_share, b.pit_share);
    d[Metric::DepressionShare] = scalar(a.depression_share, b.depression_share);
    d[Metric::Landforms] = totalVariation(a.landform_share, b.landform_share);
    d[Metric::SpectralSlope] = scalar(a.spectrum.slope_1d, b.spectrum.slope_1d);
    return d;
}

}  // namespace terrasynth
