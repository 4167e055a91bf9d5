#include "terrasynth/heightfield.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace terrasynth {

HeightRange heightRange(const Heightfield& field) {
    if (field.heights.empty()) return {};
    auto [lo, hi] = std::minmax_element(field.heights.begin(), field.heights.end());
    return {*lo, *hi};
}

Status validateHeightfield(const Heightfield& field) {
    if (field.width < 1 || field.height < 1 || field.width > 65536 || field.height > 65536)
        return Status::error("absurd size " + std::to_string(field.width) + "x" + std::to_string(field.height) +
                             " (each side must be 1..65536)");
    if (field.heights.size() != static_cast<size_t>(field.width) * field.height)
        return Status::error("sample count does not match the size");
    for (double s : {field.meters_per_pixel_x, field.meters_per_pixel_y})
        if (!(s > 0.0) || s > 1.0e5 || !std::isfinite(s))
            return Status::error("meters_per_pixel must be in (0, 100000], got " + std::to_string(s));
    for (size_t i = 0; i < field.heights.size(); ++i) {
        if (!std::isfinite(field.heights[i]))
            return Status::error("non-finite height at x=" + std::to_string(i % field.width) +
                                 " y=" + std::to_string(i / field.width));
        if (std::fabs(field.heights[i]) > 1.0e5f)
            return Status::error("height " + std::to_string(field.heights[i]) + " m out of range at x=" +
                                 std::to_string(i % field.width) + " y=" + std::to_string(i / field.width));
    }
    return Status::ok();
}

namespace {

// Resamples one line of `n_in` samples (stride apart) to `n_out`. `ratio` = n_in / n_out.
// Downsampling first blurs with a Gaussian of sigma 0.5*ratio so the output carries no aliasing.
void resampleLine(const float* in, int n_in, size_t in_stride, float* out, int n_out, size_t out_stride,
                  std::vector<float>& scratch) {
    const double ratio = static_cast<double>(n_in) / n_out;
    scratch.resize(n_in);
    if (ratio > 1.0) {
        const double sigma = 0.5 * ratio;
        const int radius = static_cast<int>(std::ceil(3.0 * sigma));
        for (int i = 0; i < n_in; ++i) {
            double sum = 0.0, weight = 0.0;
            for (int k = -radius; k <= radius; ++k) {
                const int j = std::clamp(i + k, 0, n_in - 1);
                const double w = std::exp(-0.5 * k * k / (sigma * sigma));
                sum += w * in[j * in_stride];
                weight += w;
            }
            scratch[i] = static_cast<float>(sum / weight);
        }
    } else {
        for (int i = 0; i < n_in; ++i) scratch[i] = in[i * in_stride];
    }
    auto sample = [&](int j) { return static_cast<double>(scratch[std::clamp(j, 0, n_in - 1)]); };
    for (int o = 0; o < n_out; ++o) {
        const double x = (o + 0.5) * ratio - 0.5;
        const int x0 = static_cast<int>(std::floor(x));
        const double t = x - x0;
        double value;
        if (ratio > 1.0) {
            value = sample(x0) * (1.0 - t) + sample(x0 + 1) * t;
        } else {  // Catmull-Rom
            const double p0 = sample(x0 - 1), p1 = sample(x0), p2 = sample(x0 + 1), p3 = sample(x0 + 2);
            value = p1 + 0.5 * t * (p2 - p0 + t * (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3 + t * (3.0 * (p1 - p2) + p3 - p0)));
        }
        out[o * out_stride] = static_cast<float>(value);
    }
}

}  // namespace

Heightfield resampleToSpacing(const Heightfield& field, double meters_per_pixel) {
    TERRASYNTH_REQUIRE(meters_per_pixel > 0.0, "target spacing must be positive");
    const bool same_x = std::fabs(field.meters_per_pixel_x / meters_per_pixel - 1.0) < 1e-3;
    const bool same_y = std::fabs(field.meters_per_pixel_y / meters_per_pixel - 1.0) < 1e-3;
    if (same_x && same_y) {
        Heightfield copy = field;
        copy.meters_per_pixel_x = copy.meters_per_pixel_y = meters_per_pixel;
        return copy;
    }
    const int out_w = std::max(1, static_cast<int>(std::lround(field.width * field.meters_per_pixel_x / meters_per_pixel)));
    const int out_h = std::max(1, static_cast<int>(std::lround(field.height * field.meters_per_pixel_y / meters_per_pixel)));
    std::vector<float> scratch;
    Heightfield rows(out_w, field.height, meters_per_pixel);
    for (int y = 0; y < field.height; ++y)
        resampleLine(&field.heights[static_cast<size_t>(y) * field.width], field.width, 1,
                     &rows.heights[static_cast<size_t>(y) * out_w], out_w, 1, scratch);
    Heightfield out(out_w, out_h, meters_per_pixel);
    for (int x = 0; x < out_w; ++x)
        resampleLine(&rows.heights[x], field.height, out_w, &out.heights[x], out_h, out_w, scratch);
    return out;
}

}  // namespace terrasynth
