// What drawing the terrain costs on this machine's rasterizer, as stock osgviewer shows it: the
// shipped project read through the osgdb plugin with its default options, the trackball
// manipulator's home view (the plugin's oblique view of the project extent), and one frame per
// iteration (cull + draw + glFinish) once every wanted tile is resident. Calibrates the game's
// figures (docs/game.md): the reference is about 120 ms per frame at 1280x720 and 80 ms at
// 640x360 on Mesa llvmpipe. Counters: draw_cpu_ms (process CPU during the frame: llvmpipe's
// threads; unlike wall time, not inflated by other processes), triangles drawn.
// Needs a display: xvfb-run -a -s "-screen 0 1280x720x24" build/bin/view_bench
#include <benchmark/benchmark.h>

#include <time.h>

#include <chrono>
#include <cstdlib>
#include <string>
#include <thread>

#include <osg/GraphicsContext>
#include <osgDB/ReadFile>
#include <osgDB/Registry>
#include <osgGA/TrackballManipulator>
#include <osgViewer/Viewer>

#include "terrasynth_plugin/terrain_node.h"

namespace {

double processCpuMs() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

struct Finish : osg::Camera::DrawCallback {
    void operator()(osg::RenderInfo&) const override { glFinish(); }
};

void BM_StockViewerHome(benchmark::State& state) {
    ::setenv("POCL_CACHE_DIR", TERRASYNTH_BENCH_POCL_CACHE, 0);
    osgDB::Registry::instance()->getLibraryFilePathList().push_front(TERRASYNTH_BENCH_OSG_LIBRARY_PATH);
    const int width = static_cast<int>(state.range(0)), height = static_cast<int>(state.range(1));
    osg::ref_ptr<osg::Node> scene = osgDB::readNodeFile(std::string(TERRASYNTH_BENCH_DATA_DIR) + "/default.tsyn");
    auto* terrain = dynamic_cast<terrasynth::plugin::TerrainNode*>(scene.get());
    if (!terrain) {
        state.SkipWithError("could not read data/default.tsyn through the plugin");
        return;
    }
    osgViewer::Viewer viewer;
    viewer.setThreadingModel(osgViewer::Viewer::SingleThreaded);
    viewer.setUpViewInWindow(0, 0, width, height);
    viewer.getCamera()->setFinalDrawCallback(new Finish);
    viewer.setSceneData(scene.get());
    viewer.setCameraManipulator(new osgGA::TrackballManipulator);
    viewer.realize();
    if (!viewer.isRealized()) {
        state.SkipWithError("no window (run under xvfb-run)");
        return;
    }
    for (int f = 0; f < 5000; ++f) {
        viewer.frame();
        if (f > 3 && terrain->settled()) break;
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    double cpu = 0.0;
    for (auto _ : state) {
        const double c0 = processCpuMs();
        viewer.frame();
        cpu += processCpuMs() - c0;
    }
    state.counters["draw_cpu_ms"] = cpu / static_cast<double>(state.iterations());
    state.counters["triangles"] = static_cast<double>(terrain->stats().drawn_triangles);
}
BENCHMARK(BM_StockViewerHome)->Args({1280, 720})->Args({640, 360})->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);

}  // namespace

BENCHMARK_MAIN();
