// The osgdb_terrasynth module as osgDB loads it: found through OSG_LIBRARY_PATH for the .tsyn
// extension, polite to foreign files, strict about its own options, and reading a real project into
// a terrain that osgconv can write.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include <osg/Geometry>
#include <osgDB/ReadFile>
#include <osgDB/Registry>

#include "terrasynth/database.h"
#include "terrasynth/project.h"
#include "terrasynth_plugin/plugin_options.h"
#include "terrasynth_plugin/terrain_node.h"
#include "test_support.h"

namespace terrasynth::plugin {
namespace {

osgDB::ReaderWriter* tsynReader() {
    static const bool path_set = [] {
        osgDB::Registry::instance()->getLibraryFilePathList().push_front(TERRASYNTH_TEST_OSG_LIBRARY_PATH);
        return true;
    }();
    (void)path_set;
    return osgDB::Registry::instance()->getReaderWriterForExtension("tsyn");
}

// Stock osgconv converts <dir>/world.tsyn with `options` into <dir>/out.osgb, which reads back
// with tiles in it.
void expectOsgconvWrites(const std::string& dir, const std::string& options) {
    const std::string cmd = std::string("OSG_LIBRARY_PATH='") + TERRASYNTH_TEST_OSG_LIBRARY_PATH + "' osgconv -O '" +
                            options + "' '" + dir + "/world.tsyn' '" + dir + "/out.osgb' > '" + dir + "/osgconv.log' 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << test::readFile(dir + "/osgconv.log");
    osg::ref_ptr<osg::Node> written = osgDB::readRefNodeFile(dir + "/out.osgb");
    ASSERT_TRUE(written.valid());
    EXPECT_GT(written->asGroup()->getNumChildren(), 0u);
}

TEST(PluginReader, LoadsForTheTsynExtension) {
    osgDB::ReaderWriter* rw = tsynReader();
    ASSERT_NE(rw, nullptr) << "osgdb_tsyn not found under " << TERRASYNTH_TEST_OSG_LIBRARY_PATH;
    EXPECT_TRUE(rw->acceptsExtension("tsyn"));
    EXPECT_FALSE(rw->acceptsExtension("osgb"));
    EXPECT_FALSE(rw->supportedOptions().empty());
}

TEST(PluginReader, ForeignAndMissingFilesAreNotErrors) {
    osgDB::ReaderWriter* rw = tsynReader();
    ASSERT_NE(rw, nullptr);
    EXPECT_EQ(rw->readNode("cow.osg").status(), osgDB::ReaderWriter::ReadResult::FILE_NOT_HANDLED);
    EXPECT_EQ(rw->readNode("no_such_dir/world.tsyn").status(), osgDB::ReaderWriter::ReadResult::FILE_NOT_FOUND);
}

TEST(PluginReader, BadOptionValuesAreReportedByName) {
    osgDB::ReaderWriter* rw = tsynReader();
    ASSERT_NE(rw, nullptr);
    const std::string path = test::scratchDir("plugin_reader_options") + "/world.tsyn";
    std::ofstream(path) << "{}";
    osg::ref_ptr<osgDB::Options> opts = new osgDB::Options("threads=2 tileSize=12 meshStep=5");
    auto r = rw->readNode(path, opts.get());
    EXPECT_EQ(r.status(), osgDB::ReaderWriter::ReadResult::ERROR_IN_READING_FILE);
    EXPECT_NE(r.message().find("meshStep"), std::string::npos) << r.message();

    auto parsed = parsePluginOptions("noTriStripPolygons TILESIZE=128, seed=7;maxLevel=3 pixelError=2.5");
    ASSERT_TRUE(parsed) << parsed.message();
    EXPECT_EQ(parsed->node.tile_size, 128);
    EXPECT_EQ(parsed->node.max_level, 3);
    EXPECT_TRUE(parsed->max_level_given);
    EXPECT_FLOAT_EQ(parsed->node.pixel_error, 2.5f);
    ASSERT_TRUE(parsed->seed.has_value());
    EXPECT_EQ(*parsed->seed, 7u);
    auto look = parsePluginOptions("sunAzimuth=200 sunElevation=30 snowLine=2500 fog=50000 typeColors=1");
    ASSERT_TRUE(look) << look.message();
    EXPECT_FLOAT_EQ(*look->sun_azimuth_deg, 200.0f);
    EXPECT_FLOAT_EQ(*look->sun_elevation_deg, 30.0f);
    EXPECT_FLOAT_EQ(*look->snow_line_m, 2500.0f);
    EXPECT_FLOAT_EQ(*look->fog_m, 50000.0f);
    EXPECT_TRUE(look->type_colors);
    for (const char* bad : {"tileSize=abc", "seed=-1", "maxLevel=2 minLevel=3", "backend=cuda", "cacheMB=0",
                            "sunElevation=100", "fog=-1", "typeColors=2"}) {
        auto p = parsePluginOptions(bad);
        EXPECT_FALSE(p) << bad;
    }
    // NaN and infinity passed the range checks: skirt=inf wrote 1281 vertices at z = -inf through
    // osgconv. Each is refused, naming the option, and the reader answers an error, not a node.
    for (const char* bad : {"skirt=inf", "sunElevation=nan", "sunAzimuth=inf", "snowLine=nan", "pixelError=nan",
                            "viewRadius=inf", "fog=nan", "mergeBudgetMs=-inf"}) {
        auto p = parsePluginOptions(bad);
        ASSERT_FALSE(p) << bad;
        const std::string name = std::string(bad).substr(0, std::string(bad).find('='));
        EXPECT_NE(p.message().find("option " + name + "="), std::string::npos) << p.message();
        EXPECT_NE(p.message().find("finite"), std::string::npos) << p.message();
    }
    osg::ref_ptr<osgDB::Options> infinite_skirt = new osgDB::Options("skirt=inf");
    auto refused = rw->readNode(path, infinite_skirt.get());
    EXPECT_EQ(refused.status(), osgDB::ReaderWriter::ReadResult::ERROR_IN_READING_FILE);
    EXPECT_NE(refused.message().find("skirt"), std::string::npos) << refused.message();
}

TEST(PluginReader, ReadsAProjectAndOsgconvWritesIt) {
    const std::string dir = test::scratchDir("plugin_reader_project");
    Project p;
    p.exemplars = {test::dataDir() + "/exemplars/orom_alaska.png"};
    p.width = p.height = 256;
    ASSERT_TRUE(saveProject(p, dir + "/world.tsyn"));
    osg::ref_ptr<osgDB::Options> opts = new osgDB::Options("tileSize=64 maxLevel=3 threads=2");
    osgDB::ReaderWriter* rw = tsynReader();
    ASSERT_NE(rw, nullptr);
    auto r = rw->readNode(dir + "/world.tsyn", opts.get());
    ASSERT_TRUE(r.success()) << r.message();
    auto* terrain = dynamic_cast<TerrainNode*>(r.getNode());
    ASSERT_NE(terrain, nullptr);
    EXPECT_GT(terrain->getNumChildren(), 0u) << "the project extent is preloaded";
    EXPECT_TRUE(terrain->getBound().valid());
    // The look follows the extent's heights; fog hides the draw radius's edge.
    const auto range = terrain->heightRange({0, 0, 256, 256});
    ASSERT_TRUE(range.has_value());
    const TerrainLook look = terrain->look();
    EXPECT_GT(look.snow_line_m, range->first);
    EXPECT_LT(look.snow_line_m, range->second);
    EXPECT_FLOAT_EQ(look.fog_visibility_m, static_cast<float>(0.9 * terrain->options().view_radius_m));
    EXPECT_EQ(look.type_colour_mix, 0.0f);
    // The home view looks at the extent from the south, from above its peaks.
    const osg::BoundingSphere home = terrain->getBound();
    EXPECT_GT(home.center().z(), range->second);
    EXPECT_NEAR(home.center().x(), 128 * terrain->layout().meters_per_pixel, 1.0);

    // Type colours: preloaded tiles carry a type id per vertex.
    osg::ref_ptr<osgDB::Options> typed = new osgDB::Options("tileSize=64 maxLevel=3 threads=2 typeColors=1");
    auto t = rw->readNode(dir + "/world.tsyn", typed.get());
    ASSERT_TRUE(t.success()) << t.message();
    auto* typed_terrain = dynamic_cast<TerrainNode*>(t.getNode());
    ASSERT_NE(typed_terrain, nullptr);
    EXPECT_GT(typed_terrain->look().type_colour_mix, 0.0f);
    ASSERT_GT(typed_terrain->getNumChildren(), 0u);
    const auto* tile = dynamic_cast<const osg::Group*>(typed_terrain->getChild(0));
    ASSERT_NE(tile, nullptr);
    const osg::Geometry* geometry = tile->getChild(0)->asGeometry();
    ASSERT_NE(geometry, nullptr);
    const auto* types = dynamic_cast<const osg::FloatArray*>(geometry->getVertexAttribArray(kTypeAttribute));
    ASSERT_NE(types, nullptr) << "no type attribute";
    for (float id : *types) EXPECT_EQ(id, 0.0f) << "one exemplar, one type: its default type";
    // What osgconv asks for first.
    EXPECT_TRUE(rw->readObject(dir + "/world.tsyn", opts.get()).success());

    // The stock converter, finding the plugin through OSG_LIBRARY_PATH.
    expectOsgconvWrites(dir, "tileSize=64 maxLevel=3 threads=2");
}

TEST(PluginReader, MaxLevelIsClampedToAPrebuiltDatabasesLevels) {
    // A valid project over a prebuilt 3-level database (levels 0..2) failed in osgconv with
    // "preload: tile 5/0/0: output level must be 0..2": the default maxLevel was clamped to the
    // project's database_levels (6 when the project does not say) instead of the database's.
    const std::string dir = test::scratchDir("plugin_reader_prebuilt");
    DatabaseBuildOptions build;
    build.levels = 2;
    build.threads = 2;
    auto db = buildDatabase({test::dataDir() + "/exemplars/orom_alaska.png"}, build);
    ASSERT_TRUE(db) << db.message();
    ASSERT_EQ(db.value()->levelCount(), 3);
    ASSERT_TRUE(saveDatabase(**db, dir + "/three.tsdb"));
    Project p;
    p.database = dir + "/three.tsdb";
    p.width = p.height = 256;
    ASSERT_TRUE(saveProject(p, dir + "/world.tsyn"));
    ASSERT_EQ(loadProject(dir + "/world.tsyn")->database_levels, 6) << "the scenario needs the default";

    osgDB::ReaderWriter* rw = tsynReader();
    ASSERT_NE(rw, nullptr);
    osg::ref_ptr<osgDB::Options> opts = new osgDB::Options("tileSize=64 threads=2");
    auto r = rw->readNode(dir + "/world.tsyn", opts.get());
    ASSERT_TRUE(r.success()) << r.message();
    auto* terrain = dynamic_cast<TerrainNode*>(r.getNode());
    ASSERT_NE(terrain, nullptr);
    EXPECT_EQ(terrain->options().max_level, 2);
    EXPECT_GT(terrain->getNumChildren(), 0u);

    // Given explicitly past the database, maxLevel is refused with the level range named.
    osg::ref_ptr<osgDB::Options> too_deep = new osgDB::Options("tileSize=64 threads=2 maxLevel=5");
    auto refused = rw->readNode(dir + "/world.tsyn", too_deep.get());
    EXPECT_FALSE(refused.success());
    EXPECT_NE(refused.message().find("0..2"), std::string::npos) << refused.message();

    expectOsgconvWrites(dir, "tileSize=64 threads=2");
}

}  // namespace
}  // namespace terrasynth::plugin
