#include "export/geotiff_writer.h"

#include <cstdint>
#include <cstring>
#include <vector>

namespace terrasynth::export_detail {

namespace {

enum : uint16_t { kAscii = 2, kShort = 3, kLong = 4, kDouble = 12 };

struct Entry {
    uint16_t tag, type;
    uint32_t count;
    std::vector<uint8_t> data;  // little-endian payload
};

template <class T>
Entry entry(uint16_t tag, uint16_t type, const std::vector<T>& values) {
    Entry e{tag, type, static_cast<uint32_t>(values.size()), {}};
    e.data.resize(values.size() * sizeof(T));
    std::memcpy(e.data.data(), values.data(), e.data.size());  // x86/ARM hosts are little-endian
    return e;
}

template <class T>
void append(std::string& out, T v) {
    out.append(reinterpret_cast<const char*>(&v), sizeof v);
}

}  // namespace

// GeoTIFF ASCII parameters end each value with '|' (and the tag's data with NUL).
constexpr char kCitation[] = "terrasynth local frame (x east, y north, metres)|";

std::string encodeGeoTiff(const Heightfield& field, double origin_x_m, double origin_y_m) {
    const uint32_t w = static_cast<uint32_t>(field.width), h = static_cast<uint32_t>(field.height);
    const uint32_t image_bytes = w * h * 4;
    const uint32_t image_offset = 8;
    // Tags in ascending order (TIFF 6.0 requires it).
    std::vector<Entry> entries = {
        entry<uint32_t>(256, kLong, {w}),                 // ImageWidth
        entry<uint32_t>(257, kLong, {h}),                 // ImageLength
        entry<uint16_t>(258, kShort, {32}),               // BitsPerSample
        entry<uint16_t>(259, kShort, {1}),                // Compression: none
        entry<uint16_t>(262, kShort, {1}),                // Photometric: min-is-black
        entry<uint32_t>(273, kLong, {image_offset}),      // StripOffsets
        entry<uint16_t>(277, kShort, {1}),                // SamplesPerPixel
        entry<uint32_t>(278, kLong, {h}),                 // RowsPerStrip
        entry<uint32_t>(279, kLong, {image_bytes}),       // StripByteCounts
        entry<uint16_t>(284, kShort, {1}),                // PlanarConfiguration: chunky
        entry<uint16_t>(339, kShort, {3}),                // SampleFormat: IEEE float
        entry<double>(33550, kDouble, {field.meters_per_pixel_x, field.meters_per_pixel_y, 0.0}),  // ModelPixelScale
        entry<double>(33922, kDouble, {0.0, 0.0, 0.0, origin_x_m, origin_y_m, 0.0}),             // ModelTiepoint
        // GeoKeyDirectory: version 1.1.0, 4 keys: GTModelType = projected, GTRasterType = pixel-is-area,
        // GTCitation (in GeoAsciiParams), ProjLinearUnits = metre (EPSG 9001). No projection: synthetic
        // terrain lies in a local metric frame, which GDAL reads as an engineering CRS in metres.
        entry<uint16_t>(34735, kShort, {1, 1, 0, 4, 1024, 0, 1, 1, 1025, 0, 1, 1, 1026, 34737,
                                        static_cast<uint16_t>(sizeof kCitation - 1), 0, 3076, 0, 1, 9001}),
        entry<char>(34737, kAscii, std::vector<char>(kCitation, kCitation + sizeof kCitation)),  // GeoAsciiParams
    };
    std::string out;
    out.reserve(image_offset + image_bytes + 512);
    out.append("II");
    append<uint16_t>(out, 42);
    const uint32_t ifd_offset = image_offset + image_bytes;
    append<uint32_t>(out, ifd_offset);
    out.append(reinterpret_cast<const char*>(field.heights.data()), image_bytes);
    // IFD, then the payloads that do not fit the 4-byte value field.
    uint32_t extra = ifd_offset + 2 + static_cast<uint32_t>(entries.size()) * 12 + 4;
    std::string payloads;
    append<uint16_t>(out, static_cast<uint16_t>(entries.size()));
    for (const Entry& e : entries) {
        append<uint16_t>(out, e.tag);
        append<uint16_t>(out, e.type);
        append<uint32_t>(out, e.count);
        if (e.data.size() <= 4) {
            std::string value(reinterpret_cast<const char*>(e.data.data()), e.data.size());
            value.resize(4, '\0');
            out += value;
        } else {
            append<uint32_t>(out, extra + static_cast<uint32_t>(payloads.size()));
            payloads.append(reinterpret_cast<const char*>(e.data.data()), e.data.size());
            if (payloads.size() % 2) payloads.push_back('\0');  // word alignment
        }
    }
    append<uint32_t>(out, 0);  // no further IFD
    out += payloads;
    return out;
}

}  // namespace terrasynth::export_detail
