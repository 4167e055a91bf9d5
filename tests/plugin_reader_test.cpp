// The osgdb_terrasynth module as osgDB loads it: found through OSG_LIBRARY_PATH for the .tsyn
// extension, polite to foreign files, strict about its own options, and (once the runtime's Terrain
// is built) reading a real project into a terrain that osgconv can write.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include <osgDB/ReadFile>
#include <osgDB/Registry>

#include "terrasynth_plugin/plugin_options.h"
#include "test_support.h"
#ifdef TERRASYNTH_TEST_HAVE_TERRAIN
#include "terrasynth/project.h"
#include "terrasynth_plugin/terrain_node.h"
#endif

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
    for (const char* bad : {"tileSize=abc", "seed=-1", "maxLevel=2 minLevel=3", "backend=cuda", "cacheMB=0"}) {
        auto p = parsePluginOptions(bad);
        EXPECT_FALSE(p) << bad;
    }
}

#ifdef TERRASYNTH_TEST_HAVE_TERRAIN
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
    // What osgconv asks for first.
    EXPECT_TRUE(rw->readObject(dir + "/world.tsyn", opts.get()).success());

    // The stock converter, finding the plugin through OSG_LIBRARY_PATH.
    const std::string cmd = std::string("OSG_LIBRARY_PATH='") + TERRASYNTH_TEST_OSG_LIBRARY_PATH +
                            "' osgconv -O 'tileSize=64 maxLevel=3 threads=2' '" + dir + "/world.tsyn' '" + dir +
                            "/out.osgb' > '" + dir + "/osgconv.log' 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << "see " << dir << "/osgconv.log";
    osg::ref_ptr<osg::Node> written = osgDB::readRefNodeFile(dir + "/out.osgb");
    ASSERT_TRUE(written.valid());
    EXPECT_GT(written->asGroup()->getNumChildren(), 0u);
}
#endif

}  // namespace
}  // namespace terrasynth::plugin
