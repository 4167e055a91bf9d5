#include "export/colors.h"

#include <png.h>

#include <algorithm>
#include <cmath>

namespace terrasynth::export_detail {

namespace {

struct Stop {
    float t, r, g, b;
};
// A conventional hypsometric ramp: lowland green, upland ochre, rock brown-grey, snow.
constexpr Stop kRamp[] = {{0.00f, 0.33f, 0.52f, 0.30f}, {0.30f, 0.62f, 0.62f, 0.38f},
                          {0.55f, 0.55f, 0.45f, 0.33f}, {0.80f, 0.60f, 0.58f, 0.56f},
                          {1.00f, 0.96f, 0.96f, 0.98f}};

// Distinct, muted colours for the first types; later ones cycle with a hue shift.
constexpr uint8_t kTypePalette[][3] = {{200, 80, 60},  {70, 110, 190}, {220, 190, 90}, {90, 160, 90},
                                       {160, 90, 170}, {80, 170, 170}, {190, 130, 70}, {140, 140, 140}};

}  // namespace

std::array<uint8_t, 3> terrainColor(float t, uint8_t type) {
    t = std::clamp(std::isfinite(t) ? t : 0.0f, 0.0f, 1.0f);
    size_t k = 1;
    while (k + 1 < std::size(kRamp) && kRamp[k].t < t) ++k;
    const Stop& a = kRamp[k - 1];
    const Stop& b = kRamp[k];
    const float w = (t - a.t) / (b.t - a.t);
    float rgb[3] = {a.r + w * (b.r - a.r), a.g + w * (b.g - a.g), a.b + w * (b.b - a.b)};
    if (type != 255) {
        const uint8_t* c = kTypePalette[type % std::size(kTypePalette)];
        const float shift = 0.15f * static_cast<float>(type / std::size(kTypePalette) % 4);
        for (int i = 0; i < 3; ++i) rgb[i] = 0.5f * rgb[i] + 0.5f * std::fmod(c[i] / 255.0f + shift, 1.0f);
    }
    std::array<uint8_t, 3> out;
    for (int i = 0; i < 3; ++i) out[i] = static_cast<uint8_t>(std::lround(std::clamp(rgb[i], 0.0f, 1.0f) * 255.0f));
    return out;
}

namespace {
void appendToString(png_structp png, png_bytep data, png_size_t length) {
    static_cast<std::string*>(png_get_io_ptr(png))->append(reinterpret_cast<const char*>(data), length);
}
}  // namespace

Result<std::string> encodePngRgb(int width, int height, const std::vector<uint8_t>& rgb) {
    std::string bytes;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!png || !info) {
        png_destroy_write_struct(&png, info ? &info : nullptr);
        return Status::error("texture PNG: out of memory");
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        return Status::error("texture PNG: libpng failed to encode");
    }
    png_set_write_fn(png, &bytes, appendToString, nullptr);
    png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8, PNG_COLOR_TYPE_RGB,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    for (int y = 0; y < height; ++y)
        png_write_row(png, const_cast<png_bytep>(&rgb[static_cast<size_t>(y) * width * 3]));
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    return bytes;
}

}  // namespace terrasynth::export_detail
