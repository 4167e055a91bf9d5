// Real DEMs in: GeoTIFF/VRT made with GDAL's own tools from a shipped exemplar, in geographic and UTM
// coordinates, with a vertical unit, with NoData voids, corrupt and without a CRS (docs/formats.md).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>

#include <nlohmann/json.hpp>

#include "terrasynth/database.h"
#include "terrasynth/heightfield_io.h"
#include "test_support.h"

using namespace terrasynth;

namespace {

// orom_rockies: 648x648 SRTM-3 pixels, 16-bit PNG whose sidecar maps 0..65535 to metres.
struct Source {
    std::string png;
    double lo = 0, hi = 0;
    Heightfield metres;
};

const Source& rockies() {
    static const Source source = [] {
        Source s;
        s.png = test::dataDir() + "/exemplars/orom_rockies.png";
        const auto side = nlohmann::json::parse(test::readFile(test::dataDir() + "/exemplars/orom_rockies.json"));
        s.lo = side["height_min_m"].get<double>(), s.hi = side["height_max_m"].get<double>();
        s.metres = test::loadExemplarField("orom_rockies");
        return s;
    }();
    return source;
}

std::string number(double v) {
    char text[64];
    std::snprintf(text, sizeof text, "%.10g", v);
    return text;
}

// Runs a GDAL command line; the test fails (with its output) if it does.
void gdal(const std::string& command) {
    const test::CliRun run = test::runCommand(command);
    ASSERT_EQ(run.exit_code, 0) << command << "\n" << run.out;
}

#define NEED_GDAL_TOOLS()                                                                                \
    if (!test::haveProgram("gdal_translate") || !test::haveProgram("gdalwarp") || !test::haveProgram("gdal_rasterize")) \
    GTEST_SKIP() << "GDAL's command-line tools are not installed (Debian gdal-bin, scripts/setup.sh)"

// The first 240x240 pixels of the PNG as a GeoTIFF in EPSG:4326, 3 arc-second pixels centred at 47 N,
// heights as the raw 16-bit values with the band scale and offset that make them metres.
std::string geographicTiff(const std::string& dir) {
    const std::string tif = dir + "/geo47.tif";
    const double arcsec3 = 3.0 / 3600.0, half = 120 * arcsec3;
    gdal("gdal_translate -q -of GTiff -srcwin 0 0 240 240 -a_srs EPSG:4326 -a_ullr " + number(10.0) + " " +
         number(47.0 + half) + " " + number(10.0 + 2 * half) + " " + number(47.0 - half) + " -a_scale " +
         number((rockies().hi - rockies().lo) / 65535.0) + " -a_offset " + number(rockies().lo) + " '" + rockies().png +
         "' '" + tif + "'");
    return tif;
}

// The whole PNG as float32 metres in UTM zone 32N with 92.6 m pixels and NoData -32768.
std::string utmTiff(const std::string& dir, const std::string& name) {
    const std::string tif = dir + "/" + name;
    const double x0 = 500000.0, y0 = 5200000.0, side = 648 * 92.6;
    gdal("gdal_translate -q -of GTiff -ot Float32 -scale 0 65535 " + number(rockies().lo) + " " + number(rockies().hi) +
         " -a_nodata -32768 -a_srs EPSG:32632 -a_ullr " + number(x0) + " " + number(y0) + " " + number(x0 + side) + " " +
         number(y0 - side) + " '" + rockies().png + "' '" + tif + "'");
    return tif;
}

double percentOff(double value, double expected) { return 100.0 * std::fabs(value - expected) / expected; }

}  // namespace

TEST(DemImport, GeographicGeoTiffHasMetreSpacingAtItsCentreLatitude) {
    NEED_GDAL_TOOLS();
    const std::string dir = test::scratchDir("dem_geographic");
    const std::string tif = geographicTiff(dir);
    auto exemplar = readExemplar(tif);
    ASSERT_TRUE(exemplar) << exemplar.message();
    // WGS84 at 47 deg: meridional radius 6369.6 km, prime vertical 6389.1 km (x cos 47 deg).
    EXPECT_NEAR(exemplar->field.meters_per_pixel_y, 92.642, 0.01);
    EXPECT_NEAR(exemplar->field.meters_per_pixel_x, 63.380, 0.01);
    EXPECT_TRUE(exemplar->nodata.empty());
    const double step = (rockies().hi - rockies().lo) / 65535.0;
    for (int y = 0; y < 240; y += 7)
        for (int x = 0; x < 240; x += 5) ASSERT_NEAR(exemplar->field.at(x, y), rockies().metres.at(x, y), 1e-3 + step * 1e-3);

    DatabaseBuildOptions options;
    options.levels = 3;
    auto db = buildDatabase(std::vector<std::string>{tif}, options);
    ASSERT_TRUE(db) << db.message();
    // Anisotropic (63.4 x 92.6 m) pixels are resampled to the coarser spacing.
    const double off = percentOff((*db)->meters_per_pixel, 92.6);
    std::printf("EPSG:4326 at 47 deg: database spacing %.3f m, %.2f%% from 92.6 m\n", (*db)->meters_per_pixel, off);
    EXPECT_LT(off, 1.0);
    EXPECT_NEAR((*db)->levels[0].rects[0].width, std::lround(240 * 63.380 / (*db)->meters_per_pixel), 1);
}

TEST(DemImport, UtmGeoTiffWarpedByGdalBuildsAtItsSpacingAndReportsItsVoids) {
    NEED_GDAL_TOOLS();
    const std::string dir = test::scratchDir("dem_utm");
    const std::string geo = geographicTiff(dir), utm = dir + "/utm.tif";
    // gdalwarp leaves NoData where the geographic rectangle does not reach the UTM grid's corners.
    gdal("gdalwarp -q -ot Float32 -t_srs EPSG:32632 -tr 92.6 92.6 -r bilinear -dstnodata -32768 '" + geo + "' '" + utm + "'");
    auto exemplar = readExemplar(utm);
    ASSERT_TRUE(exemplar) << exemplar.message();
    EXPECT_DOUBLE_EQ(exemplar->field.meters_per_pixel_x, 92.6);
    EXPECT_DOUBLE_EQ(exemplar->field.meters_per_pixel_y, 92.6);
    ASSERT_FALSE(exemplar->nodata.empty()) << "the warped corners are NoData";
    for (size_t i = 0; i < exemplar->field.size(); ++i)
        ASSERT_GT(exemplar->field.heights[i], -1000.0f) << "voids hold a fill, never the NoData value";

    const test::CliRun run = test::runTerrasynth("db build '" + utm + "' -o '" + dir + "/utm.tsdb' -q --levels 3");
    ASSERT_EQ(run.exit_code, 0) << run.out;
    EXPECT_NE(run.out.find("92.600 m/pixel"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("utm.tif: "), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("% voids (NoData), never copied"), std::string::npos) << run.out;
    std::printf("UTM 32N (gdalwarp): %s", run.out.c_str());
}

TEST(DemImport, VerticalUnitsOfAVrtAreHonoured) {
    NEED_GDAL_TOOLS();
    const std::string dir = test::scratchDir("dem_vrt_feet");
    const std::string geo = geographicTiff(dir), vrt = dir + "/feet.vrt";
    // The same raw values, scaled to feet: heights must come back in metres.
    const double scale_ft = (rockies().hi - rockies().lo) / 65535.0 / 0.3048, offset_ft = rockies().lo / 0.3048;
    gdal("gdal_translate -q -of VRT -a_scale " + number(scale_ft) + " -a_offset " + number(offset_ft) + " '" + geo + "' '" +
         vrt + "'");
    std::ifstream in(vrt);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const size_t band = text.find("<VRTRasterBand");
    ASSERT_NE(band, std::string::npos) << text;
    text.insert(text.find('>', band) + 1, "<UnitType>ft</UnitType>");
    std::ofstream(vrt) << text;
    auto exemplar = readExemplar(vrt);
    ASSERT_TRUE(exemplar) << exemplar.message();
    for (int y = 0; y < 240; y += 11)
        for (int x = 0; x < 240; x += 13) ASSERT_NEAR(exemplar->field.at(x, y), rockies().metres.at(x, y), 0.01);

    // An unknown unit is refused by name.
    const size_t unit = text.find("<UnitType>ft</UnitType>");
    text.replace(unit, 23, "<UnitType>furlong</UnitType>");
    std::ofstream(vrt) << text;
    auto refused = readExemplar(vrt);
    ASSERT_FALSE(refused);
    EXPECT_NE(refused.message().find("furlong"), std::string::npos) << refused.message();
    EXPECT_NE(refused.message().find(vrt), std::string::npos) << refused.message();
}

TEST(DemImport, TenPercentNoDataHoleIsNeverCopied) {
    NEED_GDAL_TOOLS();
    const std::string dir = test::scratchDir("dem_void");
    const std::string tif = utmTiff(dir, "holed.tif");
    // A 205x205-pixel square hole (10.0% of 648^2) burnt in as NoData through a GeoJSON polygon
    // (in the raster's UTM coordinates: GeoJSON's own default would be WGS84 degrees).
    const int h0 = 222, h1 = 427;
    const double x0 = 500000.0 + h0 * 92.6, x1 = 500000.0 + h1 * 92.6, y0 = 5200000.0 - h0 * 92.6, y1 = 5200000.0 - h1 * 92.6;
    std::ofstream(dir + "/hole.geojson")
        << "{\"type\":\"FeatureCollection\",\"crs\":{\"type\":\"name\",\"properties\":{\"name\":\"EPSG:32632\"}},"
           "\"features\":[{\"type\":\"Feature\",\"properties\":{},\"geometry\":"
           "{\"type\":\"Polygon\",\"coordinates\":[[["
        << number(x0) << "," << number(y0) << "],[" << number(x1) << "," << number(y0) << "],[" << number(x1) << ","
        << number(y1) << "],[" << number(x0) << "," << number(y1) << "],[" << number(x0) << "," << number(y0) << "]]]}}]}";
    gdal("gdal_rasterize -q -b 1 -burn -32768 '" + dir + "/hole.geojson' '" + tif + "'");

    const test::CliRun build = test::runTerrasynth("db build '" + tif + "' -o '" + dir + "/holed.tsdb' -q --levels 5");
    ASSERT_EQ(build.exit_code, 0) << build.out;
    EXPECT_NE(build.out.find("holed.tif: 10.0% voids (NoData), never copied"), std::string::npos) << build.out;

    for (const char* backend : {"reference", "opencl"}) {
        const std::string out = dir + "/" + backend;
        const test::CliRun synth = test::runTerrasynth("synth --db '" + dir + "/holed.tsdb' -o '" + out + ".f32' --size 320x320 --seed 7 --sources '" +
                                                       out + "_src.png' --backend " + backend);
        ASSERT_EQ(synth.exit_code, 0) << synth.out;
        auto heights = readExemplar(out + ".f32");
        ASSERT_TRUE(heights) << heights.message();
        for (float h : heights->field.heights) ASSERT_GT(h, -1000.0f) << backend << ": the NoData value shows";
        // Every output pixel's source (level-0 database pixels: the file's own at 92.6 m) lies at
        // least kInteriorMargin pixels from the hole.
        auto sources = readPng16(out + "_src.png");
        ASSERT_TRUE(sources) << sources.message();
        size_t near_hole = 0;
        for (size_t p = 0; p < sources->samples.size() / 3; ++p) {
            const int sx = sources->samples[3 * p], sy = sources->samples[3 * p + 1];
            near_hole += sx >= h0 - kInteriorMargin && sx < h1 + kInteriorMargin && sy >= h0 - kInteriorMargin &&
                         sy < h1 + kInteriorMargin;
        }
        EXPECT_EQ(near_hole, 0u) << backend << ": pixels copied from the hole or its margin";
    }

    // synth -o .tif: the same heights as a float32 GeoTIFF in a local metric CRS, which reads back
    // through GDAL at the database spacing.
    const test::CliRun geotiff = test::runTerrasynth("synth --db '" + dir + "/holed.tsdb' -o '" + dir +
                                                     "/reference.tif' --size 320x320 --seed 7 --backend reference");
    ASSERT_EQ(geotiff.exit_code, 0) << geotiff.out;
    auto from_tif = readExemplar(dir + "/reference.tif");
    ASSERT_TRUE(from_tif) << from_tif.message();
    auto from_f32 = readExemplar(dir + "/reference.f32");
    ASSERT_TRUE(from_f32) << from_f32.message();
    EXPECT_EQ(from_tif->field.heights, from_f32->field.heights);
    EXPECT_NEAR(from_tif->field.meters_per_pixel_x, 92.6, 1e-9);
    EXPECT_TRUE(from_tif->nodata.empty());
}

TEST(DemImport, VoidsAreNoMatchNoCandidateAndNoSeedInTheDatabase) {
    // No GDAL tools needed: a hole in an exemplar in memory.
    Exemplar ex;
    ex.info.name = ex.info.path = "holed";
    ex.field = test::crop(test::loadExemplarField("orom_rockies"), 0, 0, 160, 160);
    ex.nodata.assign(ex.field.size(), 0);
    for (int y = 50; y < 100; ++y)
        for (int x = 60; x < 110; ++x) ex.nodata[static_cast<size_t>(y) * 160 + x] = 1;
    double share = 0.0;
    DatabaseBuildOptions options;
    options.levels = 3;
    options.on_voids = [&](const ExemplarInfo&, double s) { share = s; };
    auto db = buildDatabase(std::vector<Exemplar>{ex}, options);
    ASSERT_TRUE(db) << db.message();
    EXPECT_NEAR(share, 2500.0 / 25600.0, 1e-12);
    const DatabaseLevel& l0 = (*db)->levels[0];
    const AtlasRect& r = l0.rects[0];
    for (int y = 0; y < r.height; ++y)
        for (int x = 0; x < r.width; ++x) {
            const size_t p = static_cast<size_t>(r.y + y) * l0.width + r.x + x;
            const bool near_hole = x >= 60 - kInteriorMargin && x < 110 + kInteriorMargin && y >= 50 - kInteriorMargin &&
                                   y < 100 + kInteriorMargin;
            ASSERT_EQ(l0.type[p] == kNoType, near_hole) << x << ", " << y;
        }
    for (const DatabaseLevel& l : (*db)->levels) {
        const AtlasRect& e = l.rects[0];
        for (int y = e.y; y < e.y + e.height; ++y)
            for (int x = e.x; x < e.x + e.width; ++x)
                ASSERT_NE(l.type[l.similar[size_t(y) * l.width + x]], kNoType) << "a match in a void";
        for (const auto& seeds : l.type_seeds)
            for (uint32_t q : seeds) ASSERT_NE(l.type[q], kNoType) << "a seed in a void";
    }
    // It round-trips through the file (kNoType inside a rectangle is valid there).
    const std::string path = test::scratchDir("dem_void_db") + "/holed.tsdb";
    ASSERT_TRUE(saveDatabase(**db, path));
    auto loaded = loadDatabase(path);
    ASSERT_TRUE(loaded) << loaded.message();
}

TEST(DemImport, CorruptAndCrslessGeoTiffsAreRefusedByName) {
    NEED_GDAL_TOOLS();
    const std::string dir = test::scratchDir("dem_refused");
    const std::string corrupt = dir + "/corrupt.tif";
    std::ofstream(corrupt, std::ios::binary) << std::string("II*\0", 4) << std::string(200, '\x7f');
    test::CliRun run = test::runTerrasynth("db build '" + corrupt + "' -o '" + dir + "/x.tsdb' -q");
    EXPECT_EQ(run.exit_code, 1) << run.out;
    EXPECT_NE(run.out.find(corrupt + ": GDAL cannot read it as a raster"), std::string::npos) << run.out;
    std::printf("corrupt: %s", run.out.c_str());

    const std::string crsless = dir + "/nocrs.tif";
    gdal("gdal_translate -q -of GTiff -srcwin 0 0 64 64 -a_ullr 0 64 64 0 '" + rockies().png + "' '" + crsless + "'");
    run = test::runTerrasynth("db build '" + crsless + "' -o '" + dir + "/x.tsdb' -q");
    EXPECT_EQ(run.exit_code, 1) << run.out;
    EXPECT_NE(run.out.find(crsless + ": no coordinate reference system"), std::string::npos) << run.out;
    std::printf("CRS-less: %s", run.out.c_str());

    // A sidecar with the spacing wins over (here: stands in for) the CRS.
    std::ofstream(dir + "/nocrs.json") << R"({"meters_per_pixel": 30, "terrain_class": "test ranges"})";
    auto exemplar = readExemplar(crsless);
    ASSERT_TRUE(exemplar) << exemplar.message();
    EXPECT_EQ(exemplar->field.meters_per_pixel_x, 30.0);
    EXPECT_EQ(exemplar->info.terrain_class, "test ranges");
}
