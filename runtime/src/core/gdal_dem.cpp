// DEM rasters through GDAL: open, georeference (spacing in metres), heights in metres, NoData voids
// found through the band's mask and filled by interpolation (GDALFillNodata) so that every height is
// finite; the mask travels with the exemplar so the database never copies from a void.
#include "core/gdal_dem.h"

#include <sys/stat.h>

#include <gdal_alg.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <memory>
#include <mutex>

#include "core/sidecar.h"
#include "terrasynth/limits.h"

namespace terrasynth::detail {
namespace {

// GDAL reports errors through a per-thread handler; this one keeps them off stderr and lets the
// reader quote the last one in its own message.
class QuietGdalErrors {
public:
    QuietGdalErrors() {
        static std::once_flag registered;
        std::call_once(registered, [] { GDALAllRegister(); });
        CPLPushErrorHandler(CPLQuietErrorHandler);
        CPLErrorReset();
    }
    ~QuietGdalErrors() { CPLPopErrorHandler(); }
    QuietGdalErrors(const QuietGdalErrors&) = delete;
    QuietGdalErrors& operator=(const QuietGdalErrors&) = delete;

    static std::string last() {
        const std::string message = CPLGetLastErrorMsg();
        return message.empty() ? "no reason given" : message;
    }
};

struct DatasetCloser {
    void operator()(GDALDataset* d) const { GDALClose(d); }
};
using DatasetPtr = std::unique_ptr<GDALDataset, DatasetCloser>;

std::string lower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

// Metres per vertical unit of the band: its unit name (GDAL's GetUnitType, free text), else the
// vertical part of a compound CRS, else metres.
Result<double> metresPerVerticalUnit(GDALRasterBand& band, const OGRSpatialReference* srs, const std::string& path) {
    const std::string unit = lower(band.GetUnitType() ? band.GetUnitType() : "");
    if (unit.empty()) {
        if (srs && srs->IsCompound()) return srs->GetTargetLinearUnits("VERT_CS");
        return 1.0;
    }
    if (unit == "m" || unit == "metre" || unit == "meter" || unit == "metres" || unit == "meters") return 1.0;
    if (unit == "ft" || unit == "foot" || unit == "feet" || unit == "international foot") return 0.3048;
    if (unit == "us-ft" || unit == "ftus" || unit == "us survey foot" || unit == "foot_us" || unit == "us_survey_foot")
        return 1200.0 / 3937.0;
    if (unit == "cm" || unit == "centimetre" || unit == "centimeter") return 0.01;
    if (unit == "dm" || unit == "decimetre" || unit == "decimeter") return 0.1;
    return Status::error(path + ": unknown vertical unit \"" + unit +
                         "\" (band 1; terrasynth reads metres, decimetres, centimetres and feet)");
}

// Ground spacing in metres of one pixel along x and y at the raster's centre.
Status spacingFromCrs(GDALDataset& dataset, const double* transform, const std::string& path, double* dx, double* dy) {
    const OGRSpatialReference* srs = dataset.GetSpatialRef();
    if (!srs || srs->IsEmpty())
        return Status::error(path + ": no coordinate reference system, so the spacing in metres is unknown; assign one "
                                    "(gdal_edit.py -a_srs EPSG:...) or give a JSON sidecar with meters_per_pixel");
    const double step_x = std::fabs(transform[1]), step_y = std::fabs(transform[5]);
    if (srs->IsGeographic()) {
        // Metres per radian of longitude and latitude at the centre latitude phi: the prime-vertical
        // radius N cos(phi) and the meridional radius M of the CRS's ellipsoid.
        const double a = srs->GetSemiMajor(), b = srs->GetSemiMinor();
        const double radians_per_unit = srs->GetAngularUnits();
        const double e2 = 1.0 - (b * b) / (a * a);
        const double phi = (transform[3] + transform[5] * dataset.GetRasterYSize() / 2.0) * radians_per_unit;
        if (!(std::fabs(phi) < 1.5707963267948966))
            return Status::error(path + ": centre latitude outside (-90, 90) degrees");
        const double w = 1.0 - e2 * std::sin(phi) * std::sin(phi);
        const double prime_vertical = a / std::sqrt(w), meridional = a * (1.0 - e2) / (w * std::sqrt(w));
        *dx = step_x * radians_per_unit * prime_vertical * std::cos(phi);
        *dy = step_y * radians_per_unit * meridional;
    } else if (srs->IsProjected() || srs->IsLocal()) {
        const double metres = srs->GetLinearUnits();
        *dx = step_x * metres;
        *dy = step_y * metres;
    } else {
        return Status::error(path + ": its CRS is neither projected nor geographic; warp it to one (gdalwarp -t_srs)");
    }
    if (!(*dx > 0.0 && *dy > 0.0 && *dx <= 1e5 && *dy <= 1e5))
        return Status::error(path + ": pixel spacing " + std::to_string(*dx) + " x " + std::to_string(*dy) +
                             " m is outside (0, 100000]");
    return Status::ok();
}

// Mirrors rows and columns so that row 0 is north and x grows east, whatever the geotransform's signs.
template <class T>
void orientNorthUp(std::vector<T>& samples, int width, int height, bool flip_x, bool flip_y) {
    if (flip_y)
        for (int y = 0; y < height / 2; ++y)
            std::swap_ranges(samples.begin() + size_t(y) * width, samples.begin() + size_t(y + 1) * width,
                             samples.begin() + size_t(height - 1 - y) * width);
    if (flip_x)
        for (int y = 0; y < height; ++y) std::reverse(samples.begin() + size_t(y) * width, samples.begin() + size_t(y + 1) * width);
}

// Interpolates the heights where `valid` is 0 from the valid ones around them (GDALFillNodata:
// inverse-distance weighting of the nearest valid pixel in each of four quadrants, no smoothing).
Status fillVoids(Heightfield& field, const std::vector<uint8_t>& valid, const std::string& path) {
    GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
    if (!mem) return Status::error(path + ": GDAL has no MEM driver to fill NoData voids");
    DatasetPtr heights(mem->Create("", field.width, field.height, 1, GDT_Float32, nullptr));
    DatasetPtr mask(mem->Create("", field.width, field.height, 1, GDT_Byte, nullptr));
    if (!heights || !mask) return Status::error(path + ": GDAL cannot allocate the NoData fill: " + QuietGdalErrors::last());
    GDALRasterBand* h = heights->GetRasterBand(1);
    GDALRasterBand* m = mask->GetRasterBand(1);
    if (h->RasterIO(GF_Write, 0, 0, field.width, field.height, field.heights.data(), field.width, field.height,
                    GDT_Float32, 0, 0) != CE_None ||
        m->RasterIO(GF_Write, 0, 0, field.width, field.height, const_cast<uint8_t*>(valid.data()), field.width,
                    field.height, GDT_Byte, 0, 0) != CE_None ||
        GDALFillNodata(h, m, std::max(field.width, field.height), 0, 0, nullptr, nullptr, nullptr) != CE_None ||
        h->RasterIO(GF_Read, 0, 0, field.width, field.height, field.heights.data(), field.width, field.height,
                    GDT_Float32, 0, 0) != CE_None)
        return Status::error(path + ": filling the NoData voids failed: " + QuietGdalErrors::last());
    return Status::ok();
}

// GDAL opens files itself and would block for ever on a named pipe: only regular files go to it
// (stat, unlike open, does not wait for a writer).
bool isRegularFile(const std::string& path) {
    struct stat st {};
    return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

}  // namespace

bool isGdalDemExtension(const std::string& extension) {
    return extension == ".tif" || extension == ".tiff" || extension == ".hgt" || extension == ".asc" || extension == ".vrt";
}

bool gdalRecognisesRaster(const std::string& path) {
    if (!isRegularFile(path)) return false;
    QuietGdalErrors quiet;
    return GDALIdentifyDriverEx(path.c_str(), GDAL_OF_RASTER, nullptr, nullptr) != nullptr;
}

Result<Exemplar> readGdalExemplar(const std::string& path) {
    if (!isRegularFile(path)) return Status::error(path + ": not a regular file");
    QuietGdalErrors quiet;
    DatasetPtr dataset(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
    if (!dataset) return Status::error(path + ": GDAL cannot read it as a raster: " + QuietGdalErrors::last());
    if (dataset->GetRasterCount() < 1) return Status::error(path + ": the raster has no bands");
    Exemplar exemplar;
    exemplar.info.name = fileStem(path);
    exemplar.info.path = path;
    Heightfield& field = exemplar.field;
    field.width = dataset->GetRasterXSize();
    field.height = dataset->GetRasterYSize();
    if (field.width < 1 || field.height < 1 || field.width > limits::kMaxImageSide || field.height > limits::kMaxImageSide ||
        static_cast<uint64_t>(field.width) * field.height > limits::kMaxImagePixels)
        return Status::error(path + ": " + std::to_string(field.width) + "x" + std::to_string(field.height) +
                             " pixels; an exemplar has at most " + std::to_string(limits::kMaxImageSide) + " per side and " +
                             std::to_string(limits::kMaxImagePixels) + " in all");

    // A sidecar that exists must be right; its spacing wins over the CRS.
    const std::string sidecar = sidecarPathFor(path);
    nlohmann::json side;
    if (pathExists(sidecar)) {
        auto json = readJsonFile(sidecar);
        if (!json) return json.status();
        side = std::move(json.value());
    }
    double transform[6] = {0, 1, 0, 0, 0, 1};
    const bool georeferenced = dataset->GetGeoTransform(transform) == CE_None;
    if (georeferenced && (transform[2] != 0.0 || transform[4] != 0.0))
        return Status::error(path + ": rotated or sheared geotransform; warp it north-up first (gdalwarp)");
    if (side.contains("meters_per_pixel")) {
        if (Status s = readSpacing(side, sidecar, &field.meters_per_pixel_x, &field.meters_per_pixel_y); !s) return s;
    } else if (!georeferenced) {
        return Status::error(path + ": no georeferencing (geotransform), so the spacing is unknown; give a JSON sidecar "
                                    "with meters_per_pixel");
    } else if (Status s = spacingFromCrs(*dataset, transform, path, &field.meters_per_pixel_x, &field.meters_per_pixel_y); !s) {
        return s;
    }

    GDALRasterBand* band = dataset->GetRasterBand(1);
    auto metres = metresPerVerticalUnit(*band, dataset->GetSpatialRef(), path);
    if (!metres) return metres.status();
    int has_scale = 0, has_offset = 0;
    const double scale = band->GetScale(&has_scale), offset = band->GetOffset(&has_offset);
    field.heights.resize(static_cast<size_t>(field.width) * field.height);
    if (band->RasterIO(GF_Read, 0, 0, field.width, field.height, field.heights.data(), field.width, field.height,
                       GDT_Float32, 0, 0) != CE_None)
        return Status::error(path + ": GDAL read failed: " + QuietGdalErrors::last());
    // The band's mask covers NoData values, alpha bands and internal masks alike (0 = no data).
    std::vector<uint8_t> valid(field.heights.size(), 255);
    if (!(band->GetMaskFlags() & GMF_ALL_VALID) &&
        band->GetMaskBand()->RasterIO(GF_Read, 0, 0, field.width, field.height, valid.data(), field.width, field.height,
                                      GDT_Byte, 0, 0) != CE_None)
        return Status::error(path + ": GDAL cannot read the NoData mask: " + QuietGdalErrors::last());
    size_t voids = 0;
    for (size_t i = 0; i < field.heights.size(); ++i) {
        float& h = field.heights[i];
        if (!std::isfinite(h)) valid[i] = 0;
        if (valid[i] == 0) {
            ++voids;
            h = 0.0f;
            continue;
        }
        h = static_cast<float>(((has_scale ? scale : 1.0) * h + (has_offset ? offset : 0.0)) * metres.value());
    }
    if (voids == field.heights.size()) return Status::error(path + ": every pixel is NoData");
    if (voids > 0) {
        if (Status s = fillVoids(field, valid, path); !s) return s;
        exemplar.nodata.resize(valid.size());
        for (size_t i = 0; i < valid.size(); ++i) exemplar.nodata[i] = valid[i] == 0 ? 1 : 0;
    }
    const bool flip_x = georeferenced && transform[1] < 0.0, flip_y = georeferenced && transform[5] > 0.0;
    orientNorthUp(field.heights, field.width, field.height, flip_x, flip_y);
    if (!exemplar.nodata.empty()) orientNorthUp(exemplar.nodata, field.width, field.height, flip_x, flip_y);

    if (!side.is_null()) {
        readProvenance(side, &exemplar.info);
        if (Status s = readTypeMask(side, sidecar, &exemplar); !s) return s;
    }
    return exemplar;
}

}  // namespace terrasynth::detail
