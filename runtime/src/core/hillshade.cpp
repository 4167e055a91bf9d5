#include <algorithm>
#include <cmath>

#include "terrasynth/file_transaction.h"
#include "terrasynth/heightfield_io.h"

namespace terrasynth {

Status stageHillshadePng(FileTransaction& transaction, const std::string& path, const Heightfield& field) {
    if (Status s = validateHeightfield(field); !s) return s.withContext(path);
    const double kPi = 3.14159265358979323846;
    const double azimuth = 315.0 * kPi / 180.0, altitude = 45.0 * kPi / 180.0;
    // Light direction in (east, south, up): azimuth measured clockwise from north.
    const double lx = std::sin(azimuth) * std::cos(altitude);
    const double ly = -std::cos(azimuth) * std::cos(altitude);
    const double lz = std::sin(altitude);
    const HeightRange range = heightRange(field);
    const double span = std::max(1e-6, static_cast<double>(range.max - range.min));
    std::vector<uint8_t> rgb(static_cast<size_t>(field.width) * field.height * 3);
    for (int y = 0; y < field.height; ++y) {
        for (int x = 0; x < field.width; ++x) {
            const double dzdx = (field.clamped(x + 1, y) - field.clamped(x - 1, y)) / (2.0 * field.meters_per_pixel_x);
            const double dzdy = (field.clamped(x, y + 1) - field.clamped(x, y - 1)) / (2.0 * field.meters_per_pixel_y);
            const double norm = std::sqrt(dzdx * dzdx + dzdy * dzdy + 1.0);
            const double shade = std::max(0.0, (-dzdx * lx - dzdy * ly + lz) / norm);
            // Hypsometric tint: green lowlands through brown to white peaks.
            const double t = (field.at(x, y) - range.min) / span;
            const double r = t < 0.5 ? 0.35 + 0.5 * t : 0.6 + 0.8 * (t - 0.5);
            const double g = t < 0.5 ? 0.55 - 0.1 * t : 0.5 + 0.9 * (t - 0.5);
            const double b = t < 0.5 ? 0.30 : 0.3 + 1.3 * (t - 0.5);
            const double light = 0.25 + 0.75 * shade;
            uint8_t* px = &rgb[(static_cast<size_t>(y) * field.width + x) * 3];
            px[0] = static_cast<uint8_t>(std::clamp(255.0 * r * light, 0.0, 255.0));
            px[1] = static_cast<uint8_t>(std::clamp(255.0 * g * light, 0.0, 255.0));
            px[2] = static_cast<uint8_t>(std::clamp(255.0 * b * light, 0.0, 255.0));
        }
    }
    return stagePng8(transaction, path, field.width, field.height, 3, rgb);
}

Status writeHillshadePng(const std::string& path, const Heightfield& field) {
    FileTransaction transaction;
    if (Status s = stageHillshadePng(transaction, path, field); !s) return s;
    return transaction.commit();
}

}  // namespace terrasynth
