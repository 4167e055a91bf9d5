// Fixed-bin histograms, their summaries, and the Wasserstein-1 / Kolmogorov-Smirnov distances
// between two of them.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "stats/binning.h"

namespace terrasynth {
namespace stats {
namespace {

// A bin layout uniform in some transform u(v) of the value: edges are v(u) at equal u steps.
struct Layout {
    int bins;
    double u_lo, u_hi;
    double scale;       // asinh scale (Curvature, ReliefM)
    bool log_distance;
};

Layout layoutOf(BinKind kind) {
    switch (kind) {
        case BinKind::SlopeDeg: return {360, 0.0, 90.0, 1.0, false};
        case BinKind::Curvature: return {400, -std::asinh(1.0 / 1e-4), std::asinh(1.0 / 1e-4), 1e-4, false};
        case BinKind::ReliefM: return {300, 0.0, std::asinh(5000.0), 1.0, false};
        case BinKind::DrainageAreaM2: return {260, 0.0, 13.0, 1.0, true};
    }
    return {1, 0.0, 1.0, 1.0, false};
}

double toU(BinKind kind, const Layout& l, double v) {
    switch (kind) {
        case BinKind::SlopeDeg: return v;
        case BinKind::Curvature:
        case BinKind::ReliefM: return std::asinh(v / l.scale);
        case BinKind::DrainageAreaM2: return std::log10(std::max(v, 1e-300));
    }
    return v;
}

double fromU(BinKind kind, const Layout& l, double u) {
    switch (kind) {
        case BinKind::SlopeDeg: return u;
        case BinKind::Curvature:
        case BinKind::ReliefM: return l.scale * std::sinh(u);
        case BinKind::DrainageAreaM2: return std::pow(10.0, u);
    }
    return u;
}

// Index of the q-quantile (nearest rank) among n sorted samples.
size_t rankOf(size_t n, double q) { return static_cast<size_t>(std::lround(q * static_cast<double>(n - 1))); }

}  // namespace

Histogram emptyHistogram(BinKind kind) {
    const Layout l = layoutOf(kind);
    Histogram h;
    h.log_distance = l.log_distance;
    h.edges.resize(l.bins + 1);
    for (int i = 0; i <= l.bins; ++i) h.edges[i] = fromU(kind, l, l.u_lo + (l.u_hi - l.u_lo) * i / l.bins);
    h.mass.assign(l.bins, 0.0);
    h.position.resize(l.bins);
    for (int i = 0; i < l.bins; ++i)
        h.position[i] = l.log_distance ? l.u_lo + (l.u_hi - l.u_lo) * (i + 0.5) / l.bins
                                       : 0.5 * (h.edges[i] + h.edges[i + 1]);
    return h;
}

Distribution describe(std::vector<double>& samples, BinKind kind) {
    Distribution d;
    d.histogram = emptyHistogram(kind);
    d.samples = samples.size();
    if (samples.empty()) return d;

    const Layout l = layoutOf(kind);
    const double inv_step = l.bins / (l.u_hi - l.u_lo);
    double sum = 0.0;
    for (double v : samples) {
        const int bin = static_cast<int>(std::floor((toU(kind, l, v) - l.u_lo) * inv_step));
        d.histogram.mass[std::clamp(bin, 0, l.bins - 1)] += 1.0;
        sum += v;
    }
    const double n = static_cast<double>(samples.size());
    for (double& m : d.histogram.mass) m /= n;
    d.mean = sum / n;
    double sq = 0.0;
    for (double v : samples) sq += (v - d.mean) * (v - d.mean);
    d.stddev = std::sqrt(sq / n);

    // Percentiles by successive partial sorts, each on the part above the previous rank: O(n).
    const auto [lo, hi] = std::minmax_element(samples.begin(), samples.end());
    d.min = *lo;
    d.max = *hi;
    size_t from = 0;
    double* out[] = {&d.p10, &d.median, &d.p90, &d.p99};
    const double qs[] = {0.10, 0.50, 0.90, 0.99};
    for (int i = 0; i < 4; ++i) {
        const size_t r = rankOf(samples.size(), qs[i]);
        std::nth_element(samples.begin() + from, samples.begin() + r, samples.end());
        *out[i] = samples[r];
        from = r;
    }
    return d;
}

}  // namespace stats

namespace {
bool sameBins(const Histogram& a, const Histogram& b) {
    return a.edges == b.edges && a.mass.size() == b.mass.size() && a.position.size() == a.mass.size() &&
           b.position.size() == b.mass.size();
}
bool isEmpty(const Histogram& h) {
    return std::all_of(h.mass.begin(), h.mass.end(), [](double m) { return m == 0.0; });
}
}  // namespace

double wasserstein1(const Histogram& a, const Histogram& b) {
    TERRASYNTH_REQUIRE(sameBins(a, b), "Wasserstein distance needs histograms with identical bins");
    if (isEmpty(a) || isEmpty(b)) return 0.0;
    // W1 = integral |F_a - F_b|; with all mass at the bin positions the CDFs are steps between them.
    double cdf_a = 0.0, cdf_b = 0.0, w = 0.0;
    for (size_t i = 0; i + 1 < a.mass.size(); ++i) {
        cdf_a += a.mass[i];
        cdf_b += b.mass[i];
        w += std::fabs(cdf_a - cdf_b) * (a.position[i + 1] - a.position[i]);
    }
    return w;
}

double kolmogorovSmirnov(const Histogram& a, const Histogram& b) {
    TERRASYNTH_REQUIRE(sameBins(a, b), "Kolmogorov-Smirnov needs histograms with identical bins");
    if (isEmpty(a) || isEmpty(b)) return 0.0;
    double cdf_a = 0.0, cdf_b = 0.0, ks = 0.0;
    for (size_t i = 0; i < a.mass.size(); ++i) {
        cdf_a += a.mass[i];
        cdf_b += b.mass[i];
        ks = std::max(ks, std::fabs(cdf_a - cdf_b));
    }
    return std::min(ks, 1.0);
}

}  // namespace terrasynth
