// Seeded procedural starting points (s3.1): gradient-noise fBm and diamond-square (Fournier et al. 1982).
#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "layers/parallel.h"
#include "layers/random.h"
#include "terrasynth/layers_tools.h"

namespace terrasynth {
namespace {

using layers::hash3;
using layers::unitFromHash;

// Perlin-style gradient noise with unit gradients; scaled by sqrt(2) so it spans about [-1, 1].
double gradientNoise(uint64_t seed, double x, double y) {
    const double fx = std::floor(x), fy = std::floor(y);
    const int64_t ix = static_cast<int64_t>(fx), iy = static_cast<int64_t>(fy);
    const double tx = x - fx, ty = y - fy;
    // 256 evenly spread unit gradients, picked by hash: no trigonometry per lattice corner.
    static const std::array<std::pair<double, double>, 256> kGradients = [] {
        std::array<std::pair<double, double>, 256> g{};
        for (int i = 0; i < 256; ++i) g[i] = {std::cos(i * 6.283185307179586 / 256), std::sin(i * 6.283185307179586 / 256)};
        return g;
    }();
    auto corner = [&](int64_t cx, int64_t cy, double dx, double dy) {
        const auto& g = kGradients[hash3(seed, cx, cy) >> 56];
        return g.first * dx + g.second * dy;
    };
    auto fade = [](double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); };
    const double u = fade(tx), v = fade(ty);
    const double n00 = corner(ix, iy, tx, ty), n10 = corner(ix + 1, iy, tx - 1, ty);
    const double n01 = corner(ix, iy + 1, tx, ty - 1), n11 = corner(ix + 1, iy + 1, tx - 1, ty - 1);
    const double a = n00 + u * (n10 - n00), b = n01 + u * (n11 - n01);
    return 1.41421356 * (a + v * (b - a));
}

Heightfield fbm(const FractalParams& p, int w, int h, double mpp) {
    Heightfield out(w, h, mpp);
    double norm = 0.0, a = 1.0;
    for (int k = 0; k < p.octaves; ++k, a *= p.gain) norm += a;
    layers::parallelFor(h, 20L * w * p.octaves, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < w; ++x) {
                double sum = 0.0, amp = 1.0, freq = 1.0 / p.wavelength_px;
                for (int k = 0; k < p.octaves; ++k) {
                    // Per-octave seed and offset so octaves do not share lattice points.
                    const uint64_t s = layers::mix64(p.seed * 1315423911ull + static_cast<uint64_t>(k));
                    sum += amp * gradientNoise(s, x * freq + 0.37 * k, y * freq + 0.71 * k);
                    amp *= p.gain;
                    freq *= p.lacunarity;
                }
                out.at(x, y) = static_cast<float>(p.offset_m + p.amplitude_m * sum / norm);
            }
    });
    return out;
}

Heightfield diamondSquare(const FractalParams& p, int w, int h, double mpp) {
    int size = 1;
    while (size + 1 < std::max(w, h)) size *= 2;
    const int n = size + 1;
    int start = 1;
    while (start * 2 <= std::min<double>(p.wavelength_px, size)) start *= 2;
    std::vector<double> g(static_cast<size_t>(n) * n, 0.0);
    auto at = [&](int x, int y) -> double& { return g[static_cast<size_t>(y) * n + x]; };
    auto rnd = [&](int x, int y) { return 2.0 * unitFromHash(hash3(p.seed, x, y)) - 1.0; };
    double norm = 0.0;
    for (int s = start; s >= 1; s /= 2) norm += std::pow(static_cast<double>(s) / start, p.roughness);
    norm += 1.0;  // the initial lattice
    for (int y = 0; y < n; y += start)
        for (int x = 0; x < n; x += start) at(x, y) = rnd(x, y);
    for (int step = start; step >= 2; step /= 2) {
        const int half = step / 2;
        const double amp = std::pow(static_cast<double>(half) / start, p.roughness);
        for (int y = half; y < n; y += step)  // diamond: square centres
            for (int x = half; x < n; x += step)
                at(x, y) = 0.25 * (at(x - half, y - half) + at(x + half, y - half) + at(x - half, y + half) +
                                   at(x + half, y + half)) + amp * rnd(x, y);
        for (int y = 0; y < n; y += half)  // square: edge midpoints
            for (int x = (y / half) % 2 == 0 ? half : 0; x < n; x += step) {
                double sum = 0.0;
                int count = 0;
                if (x >= half) sum += at(x - half, y), ++count;
                if (x + half < n) sum += at(x + half, y), ++count;
                if (y >= half) sum += at(x, y - half), ++count;
                if (y + half < n) sum += at(x, y + half), ++count;
                at(x, y) = sum / count + amp * rnd(x, y);
            }
    }
    Heightfield out(w, h, mpp);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) out.at(x, y) = static_cast<float>(p.offset_m + p.amplitude_m * at(x, y) / norm);
    return out;
}

}  // namespace

Status validateFractal(const FractalParams& p) {
    if (!(std::isfinite(p.amplitude_m) && std::fabs(p.amplitude_m) <= 1.0e4))
        return Status::error("amplitude_m: must be finite with |amplitude_m| <= 10000");
    if (!(std::isfinite(p.offset_m) && std::fabs(p.offset_m) <= 1.0e4))
        return Status::error("offset_m: must be finite with |offset_m| <= 10000");
    if (!(p.wavelength_px >= 2.0 && p.wavelength_px <= 65536.0))
        return Status::error("wavelength_px: must be in [2, 65536]");
    if (p.octaves < 1 || p.octaves > 16) return Status::error("octaves: must be in 1..16");
    if (!(p.gain > 0.0 && p.gain < 1.0)) return Status::error("gain: must be in (0, 1)");
    if (!(p.lacunarity >= 1.5 && p.lacunarity <= 4.0)) return Status::error("lacunarity: must be in [1.5, 4]");
    if (!(p.roughness > 0.0 && p.roughness <= 1.0)) return Status::error("roughness: must be in (0, 1]");
    return Status::ok();
}

Heightfield fractalHeightfield(const FractalParams& p, int width, int height, double meters_per_pixel) {
    TERRASYNTH_REQUIRE(validateFractal(p).isOk(), "invalid fractal parameters");
    TERRASYNTH_REQUIRE(width > 0 && height > 0, "empty grid");
    return p.kind == FractalKind::Fbm ? fbm(p, width, height, meters_per_pixel)
                                      : diamondSquare(p, width, height, meters_per_pixel);
}

}  // namespace terrasynth
