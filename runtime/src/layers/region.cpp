// Region coverage masks for paste, hole fill and local noise layers.
#include <algorithm>
#include <cmath>

#include "terrasynth/layers_tools.h"

namespace terrasynth {

// Pixel centres sit at integer coordinates, so a rectangle (x, width) covers pixels x..x+width-1 and
// its continuous extent is [x - 0.5, x + width - 0.5].
std::vector<float> regionMask(const Region& r, double feather_px, int width, int height) {
    std::vector<float> mask(static_cast<size_t>(width) * height, 0.0f);
    const double left = r.x - 0.5, right = r.x + r.width - 0.5, top = r.y - 0.5, bottom = r.y + r.height - 0.5;
    const double cx = 0.5 * (left + right), cy = 0.5 * (top + bottom);
    const double ax = 0.5 * r.width, ay = 0.5 * r.height;
    if (ax <= 0 || ay <= 0) return mask;
    const double ramp = std::max(1.0, feather_px);
    const int x0 = std::max(0, static_cast<int>(std::floor(left))), x1 = std::min(width, static_cast<int>(std::ceil(right)) + 1);
    const int y0 = std::max(0, static_cast<int>(std::floor(top))), y1 = std::min(height, static_cast<int>(std::ceil(bottom)) + 1);
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            double inside;  // approximate distance to the edge, positive inside
            if (r.shape == RegionShape::Rect) {
                inside = std::min(std::min(x - left, right - x), std::min(y - top, bottom - y));
            } else {
                const double dx = (x - cx) / ax, dy = (y - cy) / ay;
                inside = (1.0 - std::sqrt(dx * dx + dy * dy)) * std::min(ax, ay);
            }
            const double c = feather_px > 0 ? inside / ramp : inside + 0.5;
            mask[static_cast<size_t>(y) * width + x] = static_cast<float>(std::clamp(c, 0.0, 1.0));
        }
    return mask;
}

std::vector<uint8_t> holeMask(const HoleFillParams& p, int width, int height) {
    const std::vector<float> cover = regionMask(p.hole, 0.0, width, height);
    std::vector<uint8_t> mask(cover.size());
    for (size_t i = 0; i < cover.size(); ++i) mask[i] = cover[i] >= 0.5f ? 1 : 0;
    return mask;
}

}  // namespace terrasynth
