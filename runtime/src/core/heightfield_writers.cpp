// Heightfield writers: 16-bit PNG + sidecar, float32 + sidecar, OpenEXR (optional).
#include <cmath>
#include <cstring>

#include "core/sidecar.h"
#include "terrasynth/heightfield_io.h"

#ifdef TERRASYNTH_HAVE_OPENEXR
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#endif

namespace terrasynth {
namespace {

nlohmann::json spacingJson(const Heightfield& field) {
    return nlohmann::json::array({field.meters_per_pixel_x, field.meters_per_pixel_y});
}

}  // namespace

bool openExrAvailable() {
#ifdef TERRASYNTH_HAVE_OPENEXR
    return true;
#else
    return false;
#endif
}

Status writeHeightfieldPng16(const std::string& path, const Heightfield& field, const ExemplarInfo* info) {
    Status valid = validateHeightfield(field);
    if (!valid) return valid.withContext(path);
    const HeightRange range = heightRange(field);
    const double span = range.max > range.min ? static_cast<double>(range.max) - range.min : 1.0;
    std::vector<uint16_t> samples(field.heights.size());
    for (size_t i = 0; i < samples.size(); ++i)
        samples[i] = static_cast<uint16_t>(std::lround((field.heights[i] - range.min) / span * 65535.0));
    nlohmann::json sidecar = {
        {"file", detail::baseName(path)},
        {"width", field.width},
        {"height", field.height},
        {"height_min_m", range.min},
        {"height_max_m", range.min + span},
        {"decode", "height_m = height_min_m + value/65535*(height_max_m-height_min_m)"},
        {"meters_per_pixel", spacingJson(field)},
        {"row0", "north"},
    };
    if (info) {
        sidecar["terrain_class"] = info->terrain_class;
        sidecar["source"] = info->source;
        sidecar["license"] = info->license;
    } else {
        sidecar["source"] = "terrasynth";
    }
    // Sidecar first: a reader never sees a new PNG with a stale sidecar's range.
    Status s = writeFileAtomically(detail::sidecarPathFor(path), sidecar.dump(1) + "\n");
    if (!s) return s;
    return writePng16(path, field.width, field.height, 1, samples);
}

Status writeHeightfieldF32(const std::string& path, const Heightfield& field) {
    Status valid = validateHeightfield(field);
    if (!valid) return valid.withContext(path);
    nlohmann::json sidecar = {
        {"file", detail::baseName(path)},
        {"width", field.width},
        {"height", field.height},
        {"format", "float32 little-endian, metres, row-major, row 0 north"},
        {"meters_per_pixel", spacingJson(field)},
        {"source", "terrasynth"},
    };
    Status s = writeFileAtomically(detail::sidecarPathFor(path), sidecar.dump(1) + "\n");
    if (!s) return s;
    std::string bytes(field.heights.size() * sizeof(float), '\0');
    std::memcpy(bytes.data(), field.heights.data(), bytes.size());
    return writeFileAtomically(path, bytes);
}

Status writeHeightfieldExr(const std::string& path, const Heightfield& field) {
#ifdef TERRASYNTH_HAVE_OPENEXR
    Status valid = validateHeightfield(field);
    if (!valid) return valid.withContext(path);
    const std::string temp = path + ".tmp.exr";
    try {
        Imf::Header header(field.width, field.height);
        header.channels().insert("Y", Imf::Channel(Imf::FLOAT));
        Imf::OutputFile file(temp.c_str(), header);
        Imf::FrameBuffer frame;
        frame.insert("Y", Imf::Slice(Imf::FLOAT, (char*)field.heights.data(), sizeof(float),
                                     sizeof(float) * field.width));
        file.setFrameBuffer(frame);
        file.writePixels(field.height);
    } catch (const std::exception& e) {
        std::remove(temp.c_str());
        return Status::error(path + ": OpenEXR write failed: " + e.what());
    }
    if (std::rename(temp.c_str(), path.c_str()) != 0) return Status::error(path + ": cannot replace file");
    return Status::ok();
#else
    return Status::error(path + ": this build has no OpenEXR support (install libopenexr-dev and rebuild)");
#endif
}

Status checkHeightfieldPath(const std::string& path) {
    const std::string ext = detail::lowerExtension(path);
    if (ext == ".png" || ext == ".f32" || ext == ".raw" || ext == ".exr") return Status::ok();
    return Status::error(path + ": unknown heightmap extension \"" + ext + "\" (use .png, .f32, .raw or .exr)");
}

Status writeHeightfield(const std::string& path, const Heightfield& field) {
    if (Status s = checkHeightfieldPath(path); !s) return s;
    const std::string ext = detail::lowerExtension(path);
    if (ext == ".png") return writeHeightfieldPng16(path, field);
    if (ext == ".exr") return writeHeightfieldExr(path, field);
    return writeHeightfieldF32(path, field);
}

}  // namespace terrasynth
