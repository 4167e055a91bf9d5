// exportHeightmap: the core writers for PNG/float32/EXR, the built-in GeoTIFF writer for .tif.
#include <algorithm>
#include <cctype>

#include "export/geotiff_writer.h"
#include "terrasynth/gltf_export.h"
#include "terrasynth/heightfield_io.h"

namespace terrasynth {

namespace {
std::string lowerExtension(const std::string& path) {
    const size_t dot = path.find_last_of('.');
    const size_t slash = path.find_last_of('/');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
    std::string ext = path.substr(dot);
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    return ext;
}
}  // namespace

Status exportHeightmap(const std::string& path, const Heightfield& field, double origin_x_m, double origin_y_m) {
    if (Status s = validateHeightfield(field); !s) return s.withContext(path);
    const std::string ext = lowerExtension(path);
    if (ext == ".tif" || ext == ".tiff") {
        if (field.size() * 4 > 0xF0000000ull) return Status::error(path + ": too large for a classic TIFF");
        return writeFileAtomically(path, export_detail::encodeGeoTiff(field, origin_x_m, origin_y_m));
    }
    if (ext == ".exr" && !openExrAvailable())
        return Status::error(path + ": this build has no OpenEXR; use .png, .f32 or .tif");
    return writeHeightfield(path, field);
}

}  // namespace terrasynth
