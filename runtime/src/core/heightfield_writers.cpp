// Heightfield writers: 16-bit PNG + sidecar, float32 + sidecar, OpenEXR (optional).
#include <cmath>
#include <cstring>

#include "core/sidecar.h"
#include "terrasynth/file_transaction.h"
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

Status stageHeightfieldPng16(FileTransaction& transaction, const std::string& path, const Heightfield& field,
                             const ExemplarInfo* info) {
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
    // The sidecar is staged last: it describes the PNG, so it is the last file to change.
    if (Status s = stagePng16(transaction, path, field.width, field.height, 1, samples); !s) return s;
    return transaction.stage(detail::sidecarPathFor(path), detail::dumpJson(sidecar, 1) + "\n");
}

Status stageHeightfieldF32(FileTransaction& transaction, const std::string& path, const Heightfield& field) {
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
    std::string bytes(field.heights.size() * sizeof(float), '\0');
    std::memcpy(bytes.data(), field.heights.data(), bytes.size());
    if (Status s = transaction.stage(path, bytes); !s) return s;
    return transaction.stage(detail::sidecarPathFor(path), detail::dumpJson(sidecar, 1) + "\n");
}

Status stageHeightfieldExr(FileTransaction& transaction, const std::string& path, const Heightfield& field) {
#ifdef TERRASYNTH_HAVE_OPENEXR
    Status valid = validateHeightfield(field);
    if (!valid) return valid.withContext(path);
    return transaction.stageWith(path, [&](const std::string& temp) {
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
            return Status::error(path + ": OpenEXR write failed: " + e.what());
        }
        return Status::ok();
    });
#else
    return Status::error(path + ": this build has no OpenEXR support (install libopenexr-dev and rebuild)");
#endif
}

Status writeHeightfieldPng16(const std::string& path, const Heightfield& field, const ExemplarInfo* info) {
    FileTransaction transaction;
    if (Status s = stageHeightfieldPng16(transaction, path, field, info); !s) return s;
    return transaction.commit();
}

Status writeHeightfieldF32(const std::string& path, const Heightfield& field) {
    FileTransaction transaction;
    if (Status s = stageHeightfieldF32(transaction, path, field); !s) return s;
    return transaction.commit();
}

Status writeHeightfieldExr(const std::string& path, const Heightfield& field) {
    FileTransaction transaction;
    if (Status s = stageHeightfieldExr(transaction, path, field); !s) return s;
    return transaction.commit();
}

Status checkHeightfieldPath(const std::string& path) {
    const std::string ext = detail::lowerExtension(path);
    if (ext == ".png" || ext == ".f32" || ext == ".raw" || ext == ".exr") return Status::ok();
    return Status::error(path + ": unknown heightmap extension \"" + ext + "\" (use .png, .f32, .raw or .exr)");
}

Status stageHeightfield(FileTransaction& transaction, const std::string& path, const Heightfield& field) {
    if (Status s = checkHeightfieldPath(path); !s) return s;
    const std::string ext = detail::lowerExtension(path);
    if (ext == ".png") return stageHeightfieldPng16(transaction, path, field);
    if (ext == ".exr") return stageHeightfieldExr(transaction, path, field);
    return stageHeightfieldF32(transaction, path, field);
}

Status writeHeightfield(const std::string& path, const Heightfield& field) {
    FileTransaction transaction;
    if (Status s = stageHeightfield(transaction, path, field); !s) return s;
    return transaction.commit();
}

}  // namespace terrasynth
