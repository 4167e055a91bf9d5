// libpng wrappers: 8- and 16-bit grayscale/RGB(A), in memory, errors reported (never longjmp out).
#include <png.h>

#include <csetjmp>
#include <cstring>

#include "terrasynth/file_transaction.h"
#include "terrasynth/heightfield_io.h"
#include "terrasynth/limits.h"

namespace terrasynth {
namespace {

struct ReadCursor {
    const std::string* bytes;
    size_t offset;
};

void readFromMemory(png_structp png, png_bytep out, png_size_t count) {
    auto* cursor = static_cast<ReadCursor*>(png_get_io_ptr(png));
    if (cursor->offset + count > cursor->bytes->size()) png_error(png, "file is truncated");
    std::memcpy(out, cursor->bytes->data() + cursor->offset, count);
    cursor->offset += count;
}

void writeToString(png_structp png, png_bytep data, png_size_t count) {
    static_cast<std::string*>(png_get_io_ptr(png))->append(reinterpret_cast<char*>(data), count);
}
void flushNothing(png_structp) {}

void storeErrorMessage(png_structp png, png_const_charp message) {
    auto* slot = static_cast<std::string*>(png_get_error_ptr(png));
    *slot = message;
    png_longjmp(png, 1);
}
void ignoreWarning(png_structp, png_const_charp) {}

struct DecodedPng {
    int width = 0, height = 0, channels = 0, bit_depth = 0;
    std::vector<uint8_t> raw;  // big-endian rows as libpng delivers them
};

Result<DecodedPng> decodePng(const std::string& path) {
    auto bytes = readFileBytes(path);
    if (!bytes) return bytes.status();
    const std::string& data = bytes.value();
    if (data.size() < 8 || png_sig_cmp(reinterpret_cast<png_const_bytep>(data.data()), 0, 8) != 0)
        return Status::error(path + ": not a PNG file");
    std::string error;
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &error, storeErrorMessage, ignoreWarning);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!png || !info) {
        png_destroy_read_struct(&png, &info, nullptr);
        return Status::error(path + ": out of memory creating PNG decoder");
    }
    DecodedPng out;
    std::vector<png_bytep> rows;
    ReadCursor cursor{&data, 0};
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, nullptr);
        return Status::error(path + ": corrupt PNG: " + error);
    }
    png_set_read_fn(png, &cursor, readFromMemory);
    png_read_info(png, info);
    png_uint_32 w = 0, h = 0;
    int depth = 0, color = 0;
    png_get_IHDR(png, info, &w, &h, &depth, &color, nullptr, nullptr, nullptr);
    // Checked against the header before anything is allocated: the size limits, and what the file
    // can hold at all (rows of filtered samples from a deflate stream no larger than the file).
    const uint64_t pixels = static_cast<uint64_t>(w) * h;
    const uint64_t encoded_bytes = (static_cast<uint64_t>(png_get_rowbytes(png, info)) + 1) * h;
    if (w == 0 || h == 0 || w > static_cast<png_uint_32>(limits::kMaxImageSide) ||
        h > static_cast<png_uint_32>(limits::kMaxImageSide) || pixels > limits::kMaxImagePixels) {
        png_destroy_read_struct(&png, &info, nullptr);
        return Status::error(path + ": PNG header claims " + std::to_string(w) + "x" + std::to_string(h) +
                             " pixels (at most " + std::to_string(limits::kMaxImageSide) + " per side and " +
                             std::to_string(limits::kMaxImagePixels) + " in all)");
    }
    if (encoded_bytes > static_cast<uint64_t>(data.size()) * limits::kMaxDeflateExpansion) {
        png_destroy_read_struct(&png, &info, nullptr);
        return Status::error(path + ": PNG header claims " + std::to_string(w) + "x" + std::to_string(h) +
                             " pixels, more than a " + std::to_string(data.size()) + "-byte file can hold (corrupt or truncated)");
    }
    if (color == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
    if (color == PNG_COLOR_TYPE_GRAY && depth < 8) png_set_expand_gray_1_2_4_to_8(png);
    png_read_update_info(png, info);
    out.width = static_cast<int>(w);
    out.height = static_cast<int>(h);
    out.channels = png_get_channels(png, info);
    out.bit_depth = png_get_bit_depth(png, info);
    const size_t stride = png_get_rowbytes(png, info);
    out.raw.resize(stride * h);
    rows.resize(h);
    for (png_uint_32 y = 0; y < h; ++y) rows[y] = out.raw.data() + stride * y;
    png_read_image(png, rows.data());
    png_read_end(png, nullptr);
    png_destroy_read_struct(&png, &info, nullptr);
    return out;
}

const char* describeChannels(int channels) {
    switch (channels) {
        case 1: return "gray";
        case 2: return "gray+alpha";
        case 3: return "RGB";
        default: return "RGBA";
    }
}

Result<std::string> encodePng(int width, int height, int channels, int depth, const uint8_t* big_endian_rows) {
    TERRASYNTH_REQUIRE(width > 0 && height > 0 && channels >= 1 && channels <= 4, "bad PNG layout");
    std::string encoded;
    std::string error;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &error, storeErrorMessage, ignoreWarning);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!png || !info) {
        png_destroy_write_struct(&png, &info);
        return Status::error("out of memory creating a PNG encoder");
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        return Status::error("PNG encoding failed: " + error);
    }
    static const int kColorTypes[] = {PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
                                      PNG_COLOR_TYPE_RGB_ALPHA};
    png_set_write_fn(png, &encoded, writeToString, flushNothing);
    png_set_IHDR(png, info, width, height, depth, kColorTypes[channels - 1], PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_set_compression_level(png, 4);  // heightmaps compress little beyond this; keep writes fast
    png_write_info(png, info);
    const size_t stride = static_cast<size_t>(width) * channels * (depth / 8);
    for (int y = 0; y < height; ++y)
        png_write_row(png, const_cast<png_bytep>(big_endian_rows + stride * y));
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    return encoded;
}

std::vector<uint8_t> bigEndian16(const std::vector<uint16_t>& samples) {
    std::vector<uint8_t> big_endian(samples.size() * 2);
    for (size_t i = 0; i < samples.size(); ++i) {
        big_endian[2 * i] = static_cast<uint8_t>(samples[i] >> 8);
        big_endian[2 * i + 1] = static_cast<uint8_t>(samples[i] & 0xff);
    }
    return big_endian;
}

}  // namespace

Result<Image16> readPng16(const std::string& path) {
    auto decoded = decodePng(path);
    if (!decoded) return decoded.status();
    const DecodedPng& png = decoded.value();
    if (png.bit_depth != 16)
        return Status::error(path + ": expected a 16-bit PNG, found " + std::to_string(png.bit_depth) + "-bit " +
                             describeChannels(png.channels));
    Image16 image{png.width, png.height, png.channels, {}};
    image.samples.resize(static_cast<size_t>(png.width) * png.height * png.channels);
    for (size_t i = 0; i < image.samples.size(); ++i)
        image.samples[i] = static_cast<uint16_t>((png.raw[2 * i] << 8) | png.raw[2 * i + 1]);
    return image;
}

Result<Image8> readPng8(const std::string& path) {
    auto decoded = decodePng(path);
    if (!decoded) return decoded.status();
    DecodedPng& png = decoded.value();
    if (png.bit_depth != 8)
        return Status::error(path + ": expected an 8-bit PNG, found " + std::to_string(png.bit_depth) + "-bit");
    return Image8{png.width, png.height, png.channels, std::move(png.raw)};
}

Result<std::string> encodePng16(int width, int height, int channels, const std::vector<uint16_t>& samples) {
    TERRASYNTH_REQUIRE(samples.size() == static_cast<size_t>(width) * height * channels, "sample count");
    return encodePng(width, height, channels, 16, bigEndian16(samples).data());
}

Result<std::string> encodePng8(int width, int height, int channels, const std::vector<uint8_t>& samples) {
    TERRASYNTH_REQUIRE(samples.size() == static_cast<size_t>(width) * height * channels, "sample count");
    return encodePng(width, height, channels, 8, samples.data());
}

Status stagePng16(FileTransaction& transaction, const std::string& path, int width, int height, int channels,
                  const std::vector<uint16_t>& samples) {
    auto encoded = encodePng16(width, height, channels, samples);
    if (!encoded) return encoded.status().withContext(path);
    return transaction.stage(path, encoded.value());
}

Status stagePng8(FileTransaction& transaction, const std::string& path, int width, int height, int channels,
                 const std::vector<uint8_t>& samples) {
    auto encoded = encodePng8(width, height, channels, samples);
    if (!encoded) return encoded.status().withContext(path);
    return transaction.stage(path, encoded.value());
}

Status writePng16(const std::string& path, int width, int height, int channels,
                  const std::vector<uint16_t>& samples) {
    FileTransaction transaction;
    if (Status s = stagePng16(transaction, path, width, height, channels, samples); !s) return s;
    return transaction.commit();
}

Status writePng8(const std::string& path, int width, int height, int channels,
                 const std::vector<uint8_t>& samples) {
    FileTransaction transaction;
    if (Status s = stagePng8(transaction, path, width, height, channels, samples); !s) return s;
    return transaction.commit();
}

}  // namespace terrasynth
