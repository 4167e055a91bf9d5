// exportHeightmap: the core writers for PNG/float32/EXR, the built-in GeoTIFF writer for .tif.
#include <algorithm>
#include <cctype>

#include "core/sidecar.h"
#include "export/geotiff_writer.h"
#include "terrasynth/gltf_export.h"
#include "terrasynth/heightfield_io.h"

namespace terrasynth {

using detail::lowerExtension;

Status checkHeightmapExportPath(const std::string& path) {
    const std::string ext = lowerExtension(path);
    if (ext == ".tif" || ext == ".tiff") return Status::ok();
    if (ext == ".exr" && !openExrAvailable())
        return Status::error(path + ": this build has no OpenEXR; use .png, .f32 or .tif");
    return checkHeightfieldPath(path);
}

Status stageHeightmapExport(FileTransaction& transaction, const std::string& path, const Heightfield& field,
                            double origin_x_m, double origin_y_m) {
    if (Status s = checkHeightmapExportPath(path); !s) return s;
    if (Status s = validateHeightfield(field); !s) return s.withContext(path);
    const std::string ext = lowerExtension(path);
    if (ext == ".tif" || ext == ".tiff") {
        if (field.size() * 4 > 0xF0000000ull) return Status::error(path + ": too large for a classic TIFF");
        return transaction.stage(path, export_detail::encodeGeoTiff(field, origin_x_m, origin_y_m));
    }
    return stageHeightfield(transaction, path, field);
}

Status exportHeightmap(const std::string& path, const Heightfield& field, double origin_x_m, double origin_y_m) {
    FileTransaction transaction;
    if (Status s = stageHeightmapExport(transaction, path, field, origin_x_m, origin_y_m); !s) return s;
    return transaction.commit();
}

Status stageHeightmapExport(FileTransaction& transaction, const std::string& path, const Heightfield& field,
                            const PixelWindow& window) {
    return stageHeightmapExport(transaction, path, field, window.x * field.meters_per_pixel_x,
                                -window.y * field.meters_per_pixel_y);
}

Status exportHeightmap(const std::string& path, const Heightfield& field, const PixelWindow& window) {
    FileTransaction transaction;
    if (Status s = stageHeightmapExport(transaction, path, field, window); !s) return s;
    return transaction.commit();
}

}  // namespace terrasynth
