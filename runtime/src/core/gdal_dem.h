// Private: DEM rasters through GDAL (GeoTIFF, SRTM .hgt, Esri ASCII grid, VRT and whatever else GDAL
// reads), with the spacing in metres from the raster's CRS, heights in metres from the band's unit,
// scale and offset, and NoData voids as a mask (docs/formats.md).
#pragma once

#include <string>

#include "terrasynth/heightfield_io.h"

namespace terrasynth::detail {

// Whether `extension` (lower case, with its dot) names a DEM format read through GDAL with no
// sidecar: .tif, .tiff, .hgt, .asc, .vrt. Other extensions still reach GDAL through readExemplar.
bool isGdalDemExtension(const std::string& extension);

// Whether one of GDAL's raster drivers recognises `path` (without opening it as a dataset).
bool gdalRecognisesRaster(const std::string& path);

// Reads band 1 of `path`. A JSON sidecar beside it (same stem) may give meters_per_pixel, which then
// wins over the CRS, and the usual provenance and type mask. Without one the raster needs a
// north-up geotransform and a CRS: projected or local ones give the spacing in their linear unit,
// geographic ones in metres at the raster's centre latitude on the CRS's ellipsoid. Errors name the
// file and say what is missing.
Result<Exemplar> readGdalExemplar(const std::string& path);

}  // namespace terrasynth::detail
