// A minimal float32 GeoTIFF writer (baseline TIFF, one uncompressed strip, GeoTIFF 1.0 keys), so
// heightmaps export as GeoTIFF without GDAL.
#pragma once

#include <string>

#include "terrasynth/heightfield.h"

namespace terrasynth::export_detail {

// Bytes of a little-endian TIFF: width x height float32 samples, ModelPixelScale = spacing,
// ModelTiepoint (0,0) -> (origin_x_m, origin_y_m), pixel-is-area, a local metric frame (projected
// model in metres, no projection; GDAL reads it as an engineering CRS named by its citation).
std::string encodeGeoTiff(const Heightfield& field, double origin_x_m, double origin_y_m);

}  // namespace terrasynth::export_detail
