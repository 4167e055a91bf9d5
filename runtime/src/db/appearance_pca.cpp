// Appearance space (Lefebvre & Hoppe 2006; Gain et al. 2015 s4): PCA of Gaussian-weighted 5x5
// height neighbourhoods. We fit the PCA to neighbourhoods with their weighted mean removed, and
// store that mean as mode 0: then a height offset h (eq. 4-5) moves mode 0 only, exactly.
#include <algorithm>
#include <cmath>

#include "db/db_internal.h"

namespace terrasynth::db {

const std::array<float, kNeighbourhoodSize>& neighbourhoodWeights() {
    static const std::array<float, kNeighbourhoodSize> weights = [] {
        std::array<float, kNeighbourhoodSize> w{};
        const double sigma = 1.25;  // the 5x5 window spans about +-1.6 sigma
        double sum = 0.0;
        for (int dy = -2; dy <= 2; ++dy)
            for (int dx = -2; dx <= 2; ++dx) sum += std::exp(-(dx * dx + dy * dy) / (2 * sigma * sigma));
        for (int dy = -2; dy <= 2; ++dy)
            for (int dx = -2; dx <= 2; ++dx)
                w[(dy + 2) * 5 + dx + 2] = static_cast<float>(std::exp(-(dx * dx + dy * dy) / (2 * sigma * sigma)) / sum);
        return w;
    }();
    return weights;
}

NeighbourhoodFeatures extractNeighbourhoods(const Heightfield& level, int threads) {
    const auto& w = neighbourhoodWeights();
    std::array<float, kNeighbourhoodSize> root{};
    for (int k = 0; k < kNeighbourhoodSize; ++k) root[k] = std::sqrt(w[k]);
    NeighbourhoodFeatures f;
    f.width = level.width;
    f.height = level.height;
    f.mean.resize(level.size());
    f.deviations.resize(level.size() * kNeighbourhoodSize);
    parallelRows(level.height, threads, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y) {
            for (int x = 0; x < level.width; ++x) {
                float window[kNeighbourhoodSize];
                double mean = 0.0;
                for (int k = 0; k < kNeighbourhoodSize; ++k) {
                    window[k] = level.clamped(x + k % 5 - 2, y + k / 5 - 2);
                    mean += w[k] * window[k];
                }
                const size_t i = static_cast<size_t>(y) * level.width + x;
                f.mean[i] = static_cast<float>(mean);
                float* d = &f.deviations[i * kNeighbourhoodSize];
                for (int k = 0; k < kNeighbourhoodSize; ++k) d[k] = root[k] * static_cast<float>(window[k] - mean);
            }
        }
    });
    return f;
}

namespace {

// Cyclic Jacobi eigen-decomposition of a symmetric matrix; returns eigenvalues, fills columns of V.
void jacobiEigen(std::array<std::array<double, kNeighbourhoodSize>, kNeighbourhoodSize>& a,
                 std::array<std::array<double, kNeighbourhoodSize>, kNeighbourhoodSize>& v) {
    const int n = kNeighbourhoodSize;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) v[i][j] = i == j ? 1.0 : 0.0;
    for (int sweep = 0; sweep < 100; ++sweep) {
        double off = 0.0;
        for (int i = 0; i < n; ++i)
            for (int j = i + 1; j < n; ++j) off += a[i][j] * a[i][j];
        if (off < 1e-22) break;
        for (int p = 0; p < n; ++p) {
            for (int q = p + 1; q < n; ++q) {
                if (std::fabs(a[p][q]) < 1e-300) continue;
                const double theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
                const double t = (theta >= 0 ? 1.0 : -1.0) / (std::fabs(theta) + std::sqrt(theta * theta + 1.0));
                const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
                for (int k = 0; k < n; ++k) {
                    const double akp = a[k][p], akq = a[k][q];
                    a[k][p] = c * akp - s * akq;
                    a[k][q] = s * akp + c * akq;
                }
                for (int k = 0; k < n; ++k) {
                    const double apk = a[p][k], aqk = a[q][k];
                    a[p][k] = c * apk - s * aqk;
                    a[q][k] = s * apk + c * aqk;
                }
                for (int k = 0; k < n; ++k) {
                    const double vkp = v[k][p], vkq = v[k][q];
                    v[k][p] = c * vkp - s * vkq;
                    v[k][q] = s * vkp + c * vkq;
                }
            }
        }
    }
}

}  // namespace

PcaBasis fitPca(const std::vector<const NeighbourhoodFeatures*>& exemplars) {
    const int n = kNeighbourhoodSize;
    std::array<std::array<double, kNeighbourhoodSize>, kNeighbourhoodSize> cov{};
    size_t total = 0;
    for (const NeighbourhoodFeatures* f : exemplars) total += f->mean.size();
    // Deterministic subsample: at most ~400k neighbourhoods are plenty for a 25x25 covariance.
    const size_t stride = std::max<size_t>(1, total / 400000);
    size_t counted = 0, index = 0;
    for (const NeighbourhoodFeatures* f : exemplars) {
        for (size_t i = 0; i < f->mean.size(); ++i, ++index) {
            if (index % stride) continue;
            const float* d = &f->deviations[i * n];
            for (int r = 0; r < n; ++r)
                for (int c = r; c < n; ++c) cov[r][c] += static_cast<double>(d[r]) * d[c];
            ++counted;
        }
    }
    for (int r = 0; r < n; ++r)
        for (int c = r; c < n; ++c) cov[c][r] = cov[r][c] /= std::max<size_t>(1, counted);
    std::array<std::array<double, kNeighbourhoodSize>, kNeighbourhoodSize> vectors{};
    jacobiEigen(cov, vectors);
    std::array<int, kNeighbourhoodSize> order{};
    for (int i = 0; i < n; ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return cov[a][a] > cov[b][b]; });
    PcaBasis basis;
    for (int m = 0; m < kMatchModes; ++m) {
        const int col = order[m];
        // Deterministic sign: the largest-magnitude component is positive.
        int largest = 0;
        for (int k = 1; k < n; ++k)
            if (std::fabs(vectors[k][col]) > std::fabs(vectors[largest][col])) largest = k;
        const double sign = vectors[largest][col] < 0 ? -1.0 : 1.0;
        for (int k = 0; k < n; ++k) basis.axes[m][k] = static_cast<float>(sign * vectors[k][col]);
        basis.variance[m] = std::max(0.0, cov[col][col]);
    }
    return basis;
}

std::vector<float> projectFeatures(const NeighbourhoodFeatures& features, const PcaBasis& basis, int modes,
                                   int threads) {
    TERRASYNTH_REQUIRE(modes >= 1 && modes <= kMatchModes, "mode count");
    std::vector<float> out(features.mean.size() * modes);
    parallelRows(features.height, threads, [&](int y0, int y1) {
        for (size_t i = static_cast<size_t>(y0) * features.width; i < static_cast<size_t>(y1) * features.width; ++i) {
            const float* d = &features.deviations[i * kNeighbourhoodSize];
            for (int m = 0; m < modes; ++m) {
                float sum = 0.0f;
                for (int k = 0; k < kNeighbourhoodSize; ++k) sum += basis.axes[m][k] * d[k];
                out[i * modes + m] = sum;
            }
        }
    });
    return out;
}

}  // namespace terrasynth::db
