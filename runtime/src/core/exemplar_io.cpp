// Exemplar readers: 16-bit PNG (+ sidecar or a given scale), raw float32 + sidecar, and every other
// raster through GDAL (core/gdal_dem.h).
#include <dirent.h>
#include <unistd.h>

#include <cerrno>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/gdal_dem.h"
#include "core/sidecar.h"
#include "terrasynth/heightfield_io.h"
#include "terrasynth/limits.h"

namespace terrasynth {
namespace {

using detail::lowerExtension;
using detail::readJsonFile;
using detail::readProvenance;
using detail::readTypeMask;
using detail::requireNumber;
using detail::sidecarPathFor;

// `v` is the JSON whole number `expected`, compared without narrowing (2^32 + 648 is not 648).
bool isWholeNumber(const nlohmann::json& v, int64_t expected) {
    if (v.is_number_unsigned()) return expected >= 0 && v.get<uint64_t>() == static_cast<uint64_t>(expected);
    if (v.is_number_integer()) return v.get<int64_t>() == expected;
    return false;
}

// A sidecar's width or height: a whole number 1..kMaxImageSide.
Result<int> requireSide(const nlohmann::json& j, const char* key, const std::string& file) {
    auto it = j.find(key);
    if (it == j.end()) return Status::error(file + ": missing field \"" + key + "\"");
    if (!it->is_number_integer() || it->get<int64_t>() < 1 || it->get<int64_t>() > limits::kMaxImageSide)
        return Status::error(file + ": field \"" + key + "\" must be a whole number 1.." +
                             std::to_string(limits::kMaxImageSide));
    return static_cast<int>(it->get<int64_t>());
}

Result<Exemplar> readPngExemplar(const std::string& path, const PlainPngScale* plain) {
    auto image = readPng16(path);
    if (!image) return image.status();
    if (image->channels != 1)
        return Status::error(path + ": expected a single-channel (grayscale) 16-bit PNG, found " +
                             std::to_string(image->channels) + " channels");
    Exemplar exemplar;
    exemplar.info.name = detail::fileStem(path);
    exemplar.info.path = path;
    Heightfield& field = exemplar.field;
    field.width = image->width;
    field.height = image->height;
    field.heights.resize(image->samples.size());

    const std::string sidecar = sidecarPathFor(path);
    // A sidecar that exists must be right: a broken one is its own error, never "no sidecar".
    const bool has_sidecar = detail::pathExists(sidecar);
    auto json = has_sidecar ? readJsonFile(sidecar) : Result<nlohmann::json>(Status::error(sidecar + ": not found"));
    if (has_sidecar && !json) return json.status();
    if (json) {
        const nlohmann::json& j = json.value();
        auto lo = requireNumber(j, "height_min_m", sidecar);
        if (!lo) return lo.status();
        auto hi = requireNumber(j, "height_max_m", sidecar);
        if (!hi) return hi.status();
        if (!(hi.value() >= lo.value()))
            return Status::error(sidecar + ": height_max_m must not be below height_min_m");
        Status spacing = detail::readSpacing(j, sidecar, &field.meters_per_pixel_x, &field.meters_per_pixel_y);
        if (!spacing) return spacing;
        for (const char* key : {"width", "height"}) {
            auto it = j.find(key);
            const int actual = key[0] == 'w' ? field.width : field.height;
            if (it != j.end() && !isWholeNumber(*it, actual))
                return Status::error(sidecar + ": field \"" + key + "\" does not match the PNG (" +
                                     std::to_string(actual) + ")");
        }
        const double scale = (hi.value() - lo.value()) / 65535.0;
        for (size_t i = 0; i < field.heights.size(); ++i)
            field.heights[i] = static_cast<float>(lo.value() + image->samples[i] * scale);
        readProvenance(j, &exemplar.info);
        Status mask = readTypeMask(j, sidecar, &exemplar);
        if (!mask) return mask;
    } else if (plain) {
        if (!(plain->meters_per_pixel > 0.0))
            return Status::error(path + ": a plain PNG needs a positive horizontal spacing (meters per pixel)");
        field.meters_per_pixel_x = field.meters_per_pixel_y = plain->meters_per_pixel;
        for (size_t i = 0; i < field.heights.size(); ++i)
            field.heights[i] = static_cast<float>(plain->height_offset_m + image->samples[i] * plain->meters_per_unit);
    } else {
        return Status::error(path + ": no sidecar (" + json.message() +
                             "); give a sidecar or a vertical scale and spacing for a plain 16-bit PNG");
    }
    return exemplar;
}

Result<Exemplar> readRawF32Exemplar(const std::string& path) {
    const std::string sidecar = sidecarPathFor(path);
    if (!detail::pathExists(sidecar)) return Status::error(path + ": raw float32 needs a sidecar (" + sidecar + ")");
    auto json = readJsonFile(sidecar);
    if (!json) return json.status();
    const nlohmann::json& j = json.value();
    Exemplar exemplar;
    exemplar.info.name = detail::fileStem(path);
    exemplar.info.path = path;
    auto w = requireSide(j, "width", sidecar);
    if (!w) return w.status();
    auto h = requireSide(j, "height", sidecar);
    if (!h) return h.status();
    Heightfield& field = exemplar.field;
    field.width = w.value();
    field.height = h.value();
    if (static_cast<uint64_t>(field.width) * field.height > limits::kMaxImagePixels)
        return Status::error(sidecar + ": " + std::to_string(field.width) + "x" + std::to_string(field.height) +
                             " is more than " + std::to_string(limits::kMaxImagePixels) + " pixels");
    Status spacing = detail::readSpacing(j, sidecar, &field.meters_per_pixel_x, &field.meters_per_pixel_y);
    if (!spacing) return spacing;
    const size_t expected = static_cast<size_t>(field.width) * field.height * sizeof(float);
    auto bytes = readFileBytes(path, expected);  // a larger file is refused unread
    if (!bytes) return bytes.status();
    if (bytes->size() != expected)
        return Status::error(path + ": expected " + std::to_string(expected) + " bytes for " +
                             std::to_string(field.width) + "x" + std::to_string(field.height) +
                             " float32, found " + std::to_string(bytes->size()) + " (truncated?)");
    field.heights.resize(static_cast<size_t>(field.width) * field.height);
    std::memcpy(field.heights.data(), bytes->data(), expected);  // little-endian hosts only (x86, ARM)
    readProvenance(j, &exemplar.info);
    Status mask = readTypeMask(j, sidecar, &exemplar);
    if (!mask) return mask;
    return exemplar;
}


}  // namespace

Result<Exemplar> readExemplar(const std::string& path, const PlainPngScale* plain) {
    const std::string ext = lowerExtension(path);
    Result<Exemplar> result = Status::error(path + ": unsupported exemplar format \"" + ext +
                                            "\" (use .png or .f32/.raw with a JSON sidecar, or a raster GDAL reads: .tif, "
                                            ".hgt, .asc, .vrt, ...)");
    if (ext == ".png") {
        result = readPngExemplar(path, plain);
    } else if (ext == ".f32" || ext == ".raw") {
        result = readRawF32Exemplar(path);
    } else if (detail::isGdalDemExtension(ext) || (detail::pathExists(path) && detail::gdalRecognisesRaster(path))) {
        result = detail::readGdalExemplar(path);  // past the usual DEM formats, any raster GDAL recognises
    }
    if (!result) return result;
    Status valid = validateHeightfield(result->field);
    if (!valid) return valid.withContext(path);
    return result;
}

Result<std::vector<std::string>> listExemplarFiles(const std::string& directory) {
    DIR* dir = ::opendir(directory.c_str());
    if (!dir) return Status::error(directory + ": cannot open directory: " + std::strerror(errno));
    std::vector<std::string> files;
    const std::string prefix = directory.empty() || directory.back() == '/' ? directory : directory + "/";
    while (dirent* entry = ::readdir(dir)) {
        const std::string name = entry->d_name;
        const std::string ext = lowerExtension(name);
        const std::string full = prefix + name;
        const bool has_sidecar = ::access(sidecarPathFor(full).c_str(), R_OK) == 0;
        if (((ext == ".png" || ext == ".f32" || ext == ".raw") && has_sidecar) || detail::isGdalDemExtension(ext))
            files.push_back(full);
    }
    ::closedir(dir);
    std::sort(files.begin(), files.end());
    if (files.empty()) return Status::error(directory + ": no exemplar files (PNG/F32 with JSON sidecar, or .tif/.hgt/.asc/.vrt)");
    return files;
}

}  // namespace terrasynth
