// terrasynth/heightfield_io.h: reading exemplar DEMs and writing heightfields.
//
// Formats (docs/formats.md has the details):
//  - 16-bit grayscale PNG + JSON sidecar (same stem, .json): the shared exemplar format.
//    height_m = height_min_m + value/65535 * (height_max_m - height_min_m); row 0 is north.
//  - plain 16-bit grayscale PNG without sidecar: the caller supplies spacing and vertical scale.
//  - raw little-endian float32 (.f32 or .raw) + JSON sidecar with width, height, meters_per_pixel.
//  - any raster GDAL reads (GeoTIFF, SRTM .hgt, Esri .asc, .vrt, ...): band 1, spacing in metres from
//    its CRS (projected or local: linear unit; geographic: metres at the centre latitude), heights in
//    metres from the band's unit (metres, feet, ...), scale and offset, NoData voids as `nodata`.
//    A JSON sidecar beside it with meters_per_pixel wins over the CRS.
// Every reader validates the data (size, finite heights, spacing) and names the file in its error.
// Every writer writes to temporary files in the same folder and renames them into place together
// (file_transaction.h), so an interrupted or failed write never destroys or mismatches existing files.
#pragma once

#include <string>
#include <vector>

#include "terrasynth/file_transaction.h"
#include "terrasynth/heightfield.h"
#include "terrasynth/limits.h"
#include "terrasynth/status.h"

namespace terrasynth {

// Descriptive metadata carried alongside an exemplar (from the sidecar, when there is one).
struct ExemplarInfo {
    std::string name;            // file stem, e.g. "orom_alaska"
    std::string path;            // the file that was read
    std::string terrain_class;   // coarse type label; "" when unknown
    std::string source;          // provenance, copied verbatim
    std::string license;
};

struct Exemplar {
    ExemplarInfo info;
    Heightfield field;           // heights in metres at the file's own spacing
    // Optional painted terrain type per pixel (width*height, 0..254), empty when not painted.
    // See docs/formats.md: a sidecar key "type_mask" naming an 8-bit PNG.
    std::vector<uint8_t> type_mask;
    std::vector<std::string> type_mask_names;  // names of the mask's values, index = value
    // width*height, 1 where the file holds no height (NoData, a masked or non-finite sample), 0
    // elsewhere; empty when the file has no voids. `field` holds an interpolated fill there (finite,
    // between the heights around the void) only so that filters see plausible numbers: the database
    // builder never copies from a void (docs/formats.md).
    std::vector<uint8_t> nodata;
};

// How to read a plain 16-bit PNG that has no sidecar.
struct PlainPngScale {
    double meters_per_pixel = 0.0;   // > 0 required
    double height_offset_m = 0.0;    // height of value 0
    double meters_per_unit = 1.0;    // height step of one 16-bit unit
};

// Reads an exemplar in any supported format. A PNG without a sidecar needs `plain` (spacing > 0),
// otherwise an error explains that a sidecar or a vertical scale is required.
Result<Exemplar> readExemplar(const std::string& path, const PlainPngScale* plain = nullptr);

// Lists the exemplar files of a directory (PNG with sidecar, .f32/.raw with sidecar, .tif/.tiff,
// .hgt, .asc, .vrt),
// sorted by name so database builds are deterministic.
Result<std::vector<std::string>> listExemplarFiles(const std::string& directory);

// Writers. Heights in metres. Each write* function is its stage* twin plus a commit of its own:
// the stage* functions put the file(s) into `transaction` (image first, sidecar last) after
// validating what is written, so a program writing several outputs commits them all at once and
// on any failure leaves every previous file as it was (file_transaction.h).
// 16-bit PNG quantised over the field's range, with a sidecar in the exemplar format (so the output
// can be read back as an exemplar). `info` may be null.
Status writeHeightfieldPng16(const std::string& path, const Heightfield& field,
                             const ExemplarInfo* info = nullptr);
// Raw float32 little-endian + sidecar.
Status writeHeightfieldF32(const std::string& path, const Heightfield& field);
// OpenEXR single channel "Y" float; an error when built without OpenEXR.
Status writeHeightfieldExr(const std::string& path, const Heightfield& field);
Status stageHeightfieldPng16(FileTransaction& transaction, const std::string& path, const Heightfield& field,
                             const ExemplarInfo* info = nullptr);
Status stageHeightfieldF32(FileTransaction& transaction, const std::string& path, const Heightfield& field);
Status stageHeightfieldExr(FileTransaction& transaction, const std::string& path, const Heightfield& field);
Status stageHeightfield(FileTransaction& transaction, const std::string& path, const Heightfield& field);
// Picks the writer from the extension (.png, .f32/.raw, .exr, any letter case); an error names
// unknown extensions.
Status writeHeightfield(const std::string& path, const Heightfield& field);
// What writeHeightfield would say about `path`'s extension, without touching the disk (check before
// spending time on what is to be written).
Status checkHeightfieldPath(const std::string& path);
bool openExrAvailable();

// 8-bit RGB hillshade (sun azimuth 315 deg, altitude 45 deg) with a soft hypsometric tint, for
// looking at results. Slopes use the field's true spacing.
Status writeHillshadePng(const std::string& path, const Heightfield& field);
Status stageHillshadePng(FileTransaction& transaction, const std::string& path, const Heightfield& field);

// Low-level image writers used by other stages (sources maps, masks). Row-major samples.
// The encoders return the PNG file's bytes (for FileTransaction); the writers write them atomically.
Result<std::string> encodePng16(int width, int height, int channels, const std::vector<uint16_t>& samples);
Result<std::string> encodePng8(int width, int height, int channels, const std::vector<uint8_t>& samples);
Status writePng16(const std::string& path, int width, int height, int channels,
                  const std::vector<uint16_t>& samples);
Status writePng8(const std::string& path, int width, int height, int channels,
                 const std::vector<uint8_t>& samples);
Status stagePng16(FileTransaction& transaction, const std::string& path, int width, int height, int channels,
                  const std::vector<uint16_t>& samples);
Status stagePng8(FileTransaction& transaction, const std::string& path, int width, int height, int channels,
                 const std::vector<uint8_t>& samples);
struct Image16 {
    int width = 0, height = 0, channels = 0;
    std::vector<uint16_t> samples;
};
struct Image8 {
    int width = 0, height = 0, channels = 0;
    std::vector<uint8_t> samples;
};
Result<Image16> readPng16(const std::string& path);  // 8-bit inputs are rejected
Result<Image8> readPng8(const std::string& path);    // 16-bit inputs are rejected

// Writes `bytes` to `path` atomically (temporary file + rename). The message names the path.
Status writeFileAtomically(const std::string& path, const std::string& bytes);
// The whole of a regular file (a folder, device or pipe is an error naming it), refused unread when
// it is larger than `max_bytes`.
Result<std::string> readFileBytes(const std::string& path, uint64_t max_bytes = limits::kMaxFileBytes);

}  // namespace terrasynth
