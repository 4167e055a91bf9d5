// The drainage breach on the OpenCL device (cl/cl_drainage.h, kernels/drainage.cl) against the C++
// reference, synth::breachPits, bit for bit: every float of every pixel's state (S, V, ceiling),
// on real synthesized levels of the default database at each level's radius, with and without
// carving to the window's edge, with frozen pixels taking a recorded state, constrained pixels,
// exemplars with real basins and a needed sub-window; whole syntheses with either breach (the
// default database, and shared DEMs with and without real basins); and the breach through the
// synthesizer with the default parameters.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <optional>
#include <vector>

#include "cl/cl_drainage.h"
#include "cl/cl_runtime.h"
#include "synth/drainage_breach.h"
#include "synth/level_ground.h"
#include "synth/reference_kernels.h"
#include "terrasynth/synthesizer.h"
#include "test_support.h"

namespace terrasynth {
namespace {

using synth::LevelRegion;
using synth::PixelState;

// An OpenCL context with the drainage program, as the synthesizer builds it.
struct Device {
    cl::DeviceChoice choice;
    cl::ContextHandle context;
    cl::QueueHandle queue;
    cl::ProgramHandle program;
    cl::DeviceBreach breach;
};

Device& device() {
    static Device d = [] {
        Device out;
        auto choice = cl::chooseDevice("");
        EXPECT_TRUE(choice) << choice.message();
        if (!choice) return out;
        out.choice = choice.value();
        cl_int err = CL_SUCCESS;
        const cl_context_properties props[] = {CL_CONTEXT_PLATFORM, reinterpret_cast<cl_context_properties>(out.choice.platform), 0};
        *out.context.out() = clCreateContext(props, 1, &out.choice.device, nullptr, nullptr, &err);
        EXPECT_EQ(err, CL_SUCCESS);
        *out.queue.out() = clCreateCommandQueue(out.context.get(), out.choice.device, 0, &err);
        EXPECT_EQ(err, CL_SUCCESS);
        auto program = cl::buildProgram(out.context.get(), out.choice.device, {"hash.cl", "drainage.cl"},
                                        "-cl-std=CL1.2 -cl-fp32-correctly-rounded-divide-sqrt" + cl::drainageDefines());
        EXPECT_TRUE(program) << program.message();
        if (!program) return out;
        out.program = std::move(program.value());
        const Status s = out.breach.initialise(out.context.get(), out.choice.device, out.program.get());
        EXPECT_TRUE(s) << s.message();
        return out;
    }();
    return d;
}

cl::BufferHandle upload(const void* data, size_t bytes) {
    static const float kEmpty[4] = {};
    cl_int err = CL_SUCCESS;
    cl::BufferHandle b(clCreateBuffer(device().context.get(), CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR,
                                      bytes ? bytes : sizeof kEmpty, const_cast<void*>(bytes ? data : kEmpty), &err));
    EXPECT_EQ(err, CL_SUCCESS);
    return b;
}

// A level of a real synthesis (default database, drainage off): the region and its state after
// the correction passes, from the recorded history; ceilings set to a finite value everywhere, which
// the breach must replace.
struct LevelState {
    LevelRegion region, needed;
    std::vector<PixelState> state;
    synth::PassHistory other;  // another seed's result of the same level, as a recorded drained state
};

LevelState synthesizedLevel(int level, uint32_t seed) {
    auto synthesizer = Synthesizer::create(test::defaultDatabase());
    EXPECT_TRUE(synthesizer) << synthesizer.message();
    SynthesisParams p;
    p.drainage = Drainage::Off;
    p.record_history = true;
    const PixelWindow window{-211, 97, 300, 260};
    auto run = [&](uint32_t s) {
        p.seed = s;
        auto out = synthesizer.value()->synthesize(window, p, 0, false);
        EXPECT_TRUE(out) << out.message();
        return out.value().history;
    };
    const auto history = run(seed), other = run(seed + 1);
    const DatabaseLevel& db = test::defaultDatabase()->levels[level];
    const SynthesisHistory::Level& l = history->levels[level];
    LevelState out;
    out.region = {l.x, l.y, l.width, l.height};
    // What a finer level would read: the middle of the region, a third of it each way.
    out.needed = {l.x + l.width / 3, l.y + l.height / 3, l.width / 3, l.height / 3};
    const SynthesisHistory::Pass& last = l.passes.back();
    out.state.resize(last.index.size());
    for (size_t i = 0; i < out.state.size(); ++i) {
        out.state[i].x = static_cast<float>(last.index[i] % static_cast<uint32_t>(db.width));
        out.state[i].y = static_cast<float>(last.index[i] / static_cast<uint32_t>(db.width));
        out.state[i].v = last.v[i];
        out.state[i].ceiling = 1234.5f;
    }
    out.other = {other->levels[level].passes.back().index, other->levels[level].passes.back().v};
    return out;
}

struct Case {
    bool freeze = false, constrain = false, basins = false, whole_region = false;
};

// Runs both breaches on `level` of a synthesis and compares every pixel's state bit for bit.
void expectSameBreach(int level, uint32_t seed, const Case& c) {
    SCOPED_TRACE("level " + std::to_string(level) + ", seed " + std::to_string(seed));
    Device& d = device();
    ASSERT_TRUE(d.program);
    const ExemplarDatabase& db = *test::defaultDatabase();
    const DatabaseLevel& l = db.levels[level];
    LevelState ls = synthesizedLevel(level, seed);
    const LevelRegion& region = ls.region;
    const size_t pixels = region.pixels();
    const int radius = breachRadius(level);

    // Frozen pixels: a disc of the region; they take the other seed's recorded state. Constraints:
    // another disc (a point's blend sums), overlapping the first.
    std::vector<uint8_t> coherence;
    std::vector<float> blend;
    if (c.freeze) coherence.assign(pixels, static_cast<uint8_t>(Coherence::Coherent));
    if (c.constrain) blend.assign(4 * pixels, 0.0f);
    for (int y = 0; y < region.height; ++y)
        for (int x = 0; x < region.width; ++x) {
            const size_t i = static_cast<size_t>(y) * region.width + x;
            const float fx = static_cast<float>(x) / region.width, fy = static_cast<float>(y) / region.height;
            if (c.freeze && std::hypot(fx - 0.45f, fy - 0.5f) < 0.2f) coherence[i] = static_cast<uint8_t>(Coherence::Frozen);
            if (c.constrain && std::hypot(fx - 0.6f, fy - 0.45f) < 0.15f) blend[4 * i] = 1.0f, blend[4 * i + 1] = 2000.0f;
        }
    // Every exemplar with real basins: the regional lows are kept.
    std::vector<uint8_t> basins = synth::exemplarsWithRealBasins(db);
    if (c.basins) std::fill(basins.begin(), basins.end(), 1);
    synth::DepthMargins margins;
    synth::DrainageInputs in;
    in.coherence = c.freeze ? &coherence : nullptr;
    in.drained = c.freeze ? &ls.other : nullptr;
    in.blend = c.constrain ? &blend : nullptr;
    in.depth_margin = margins.at(db, level);
    in.carve_to_edge = level >= synth::kBreachToEdgeFromLevel;
    if (!c.whole_region) in.needed = ls.needed;
    in.basin_exemplars = &basins;

    std::vector<PixelState> host = ls.state;
    const synth::BreachCounts counts = synth::breachPits(l, region, radius, in, host.data());
    if (c.basins) {  // the basins keep some regional low the database's own flags would carve
        std::vector<PixelState> carved = ls.state;
        synth::DrainageInputs without = in;
        const std::vector<uint8_t> own = synth::exemplarsWithRealBasins(db);
        without.basin_exemplars = &own;
        EXPECT_GT(synth::breachPits(l, region, radius, without, carved.data()).breached, counts.breached);
    }

    auto heights = upload(l.height_m.data(), l.height_m.size() * sizeof(float));
    auto exemplar = upload(l.exemplar.data(), l.exemplar.size());
    auto closed = upload(l.closed.data(), l.closed.size());
    auto coherence_buffer = upload(coherence.data(), coherence.size());
    auto blend_buffer = upload(blend.data(), blend.size() * sizeof(float));
    auto state = upload(ls.state.data(), pixels * sizeof(PixelState));
    const cl::DrainageLevelBuffers buffers{heights.get(), exemplar.get(), closed.get(), l.width,
                                           static_cast<cl_uint>(l.pixelCount()), static_cast<cl_uint>(l.closed.size())};
    cl::DeviceDrainageInputs on_device;
    on_device.coherence = c.freeze ? coherence_buffer.get() : nullptr;
    on_device.blend = c.constrain ? blend_buffer.get() : nullptr;
    on_device.drained = in.drained;
    on_device.depth_margin = in.depth_margin;
    on_device.carve_to_edge = in.carve_to_edge;
    on_device.needed = in.needed;
    on_device.basin_exemplars = &basins;
    const Status s = d.breach.run(d.queue.get(), buffers, region, radius, on_device, state.get());
    ASSERT_TRUE(s) << s.message();
    std::vector<PixelState> dev(pixels);
    ASSERT_EQ(clEnqueueReadBuffer(d.queue.get(), state.get(), CL_TRUE, 0, pixels * sizeof(PixelState), dev.data(), 0,
                                  nullptr, nullptr), CL_SUCCESS);

    size_t lowered = 0, frozen_taken = 0;
    for (size_t i = 0; i < pixels; ++i) {
        lowered += host[i].v < ls.state[i].v;
        frozen_taken += c.freeze && host[i].x != ls.state[i].x;
        ASSERT_EQ(std::memcmp(&host[i], &dev[i], sizeof(PixelState)), 0)
            << "pixel " << i % region.width << "," << i / region.width << " of " << region.width << "x" << region.height
            << ": host (" << host[i].x << ", " << host[i].y << ", " << host[i].v << ", " << host[i].ceiling << "), device ("
            << dev[i].x << ", " << dev[i].y << ", " << dev[i].v << ", " << dev[i].ceiling << ")";
    }
    std::printf("level %d radius %d, %dx%d: %zu pits, %zu breached, %zu pixels lowered%s\n", level, radius,
                region.width, region.height, counts.pits, counts.breached, lowered,
                c.freeze ? (", " + std::to_string(frozen_taken) + " frozen pixels took the recorded state").c_str() : "");
    // Not vacuous: the level has pits that drain, and carving lowers pixels.
    EXPECT_GT(counts.breached, 0u);
    EXPECT_GT(lowered, 0u);
    if (c.freeze) {
        EXPECT_GT(frozen_taken, 0u);
    }
}

TEST(DeviceBreach, EqualsTheReferenceAtEveryLevelAndRadius) {
    for (int level = 0; level <= 4; ++level) expectSameBreach(level, 3, {});
}

TEST(DeviceBreach, EqualsTheReferenceOverTheWholeRegionWithAnotherSeed) {
    for (int level : {0, 2, 4}) expectSameBreach(level, 8, {false, false, false, true});
}

TEST(DeviceBreach, EqualsTheReferenceWithFrozenAndConstrainedPixels) {
    for (int level : {1, 3}) expectSameBreach(level, 5, {true, true, false, false});
}

TEST(DeviceBreach, EqualsTheReferenceWithExemplarsWithRealBasins) {
    for (int level : {2, 4}) expectSameBreach(level, 6, {false, false, true, true});
}

// A synthesizer whose breach runs on the device's kernels (TERRASYNTH_CL_BREACH=device) or the
// host's reference on the mapped state (host), whatever the device.
std::unique_ptr<Synthesizer> synthesizerBreachingOn(const char* where,
                                                    std::shared_ptr<const ExemplarDatabase> db = test::defaultDatabase()) {
    ::setenv("TERRASYNTH_CL_BREACH", where, 1);
    auto s = Synthesizer::create(db);
    ::unsetenv("TERRASYNTH_CL_BREACH");
    EXPECT_TRUE(s) << s.message();
    return s ? std::move(s.value()) : nullptr;
}

// Synthesizes `w` with `p` (sources too) breaching on the device and on the host and expects the
// same bits: heights, exemplar coordinates and exemplars. The host's output; empty when either failed.
std::optional<SynthesisOutput> sameOnBothBreaches(Synthesizer& device, Synthesizer& host, const PixelWindow& w,
                                                  const SynthesisParams& p) {
    auto on_device = device.synthesize(w, p, 0, true), on_host = host.synthesize(w, p, 0, true);
    EXPECT_TRUE(on_device && on_host) << on_device.message() << on_host.message();
    if (!on_device || !on_host) return std::nullopt;
    EXPECT_EQ(on_device.value().heights.heights, on_host.value().heights.heights);
    EXPECT_EQ(on_device.value().source_x, on_host.value().source_x);
    EXPECT_EQ(on_device.value().source_y, on_host.value().source_y);
    EXPECT_EQ(on_device.value().source_exemplar, on_host.value().source_exemplar);
    return std::move(on_host.value());
}

TEST(DeviceBreach, WholeSynthesesEqualTheHostBreachBitForBit) {
    // The default settings, then a coherent edit: a point constraint over a frozen box (frozen
    // pixels take the recorded drained state, constrained ones are never carved).
    auto device = synthesizerBreachingOn("device"), host = synthesizerBreachingOn("host");
    ASSERT_TRUE(device && host);
    const PixelWindow w{-300, 170, 320, 288};
    SynthesisParams p;
    p.seed = 4;
    p.record_history = true;
    auto on_device = device->synthesize(w, p), on_host = host->synthesize(w, p);
    ASSERT_TRUE(on_device && on_host);
    EXPECT_EQ(on_device.value().heights.heights, on_host.value().heights.heights);
    SynthesisParams edited = p;
    auto constraints = std::make_shared<SynthesisConstraints>();
    constraints->points.push_back({-140.0, 300.0, on_host.value().heights.at(160, 130) + 400.0f, 0.0f, 0.0f, 70.0f});
    edited.constraints = constraints;
    edited.previous = on_host.value().history;
    auto map = std::make_shared<CoherenceMap>();
    map->x = w.x, map->y = w.y, map->width = w.width, map->height = w.height;
    map->weights.assign(static_cast<size_t>(w.width) * w.height, Coherence::Coherent);
    for (int y = 60; y < 200; ++y)
        for (int x = 40; x < 160; ++x) map->weights[static_cast<size_t>(y) * w.width + x] = Coherence::Frozen;
    for (int y = 0; y < w.height; ++y)
        for (int x = 0; x < w.width; ++x)
            if (std::hypot(x - 160.0, y - 130.0) < 70.0) map->weights[static_cast<size_t>(y) * w.width + x] = Coherence::Free;
    edited.coherence = map;
    auto edit_device = device->synthesize(w, edited), edit_host = host->synthesize(w, edited);
    ASSERT_TRUE(edit_device && edit_host);
    EXPECT_EQ(edit_device.value().heights.heights, edit_host.value().heights.heights);
    EXPECT_NE(edit_host.value().heights.heights, on_host.value().heights.heights);  // the edit did act
}

TEST(DeviceBreach, SynthesesOfADuneFieldAndAFluvialExemplarEqualTheHostBreach) {
    // Shared DEMs: orom_gobi, whose closed depressions are real (its regional lows are kept), and
    // ttb_bigtujunga, fluvial (carved to the window's edge at the coarse levels), in one database;
    // the default settings over a window at an odd origin. Heights and exemplar coordinates equal.
    auto db = loadOrBuildDatabase({test::sharedExemplarsDir() + "/orom_gobi.png",
                                   test::sharedExemplarsDir() + "/ttb_bigtujunga.png"},
                                  DatabaseBuildOptions{}, test::tmpPath("drainage_gobi_bigtujunga.tsdb"));
    ASSERT_TRUE(db) << db.message();
    const std::vector<uint8_t> basins = synth::exemplarsWithRealBasins(*db.value());
    ASSERT_EQ(basins.size(), 2u);
    EXPECT_EQ(std::count(basins.begin(), basins.end(), 1), 1);  // both rules act
    auto device = synthesizerBreachingOn("device", db.value()), host = synthesizerBreachingOn("host", db.value());
    ASSERT_TRUE(device && host);
    const PixelWindow w{-517, 333, 448, 320};
    SynthesisParams p;
    p.seed = 3;
    const std::optional<SynthesisOutput> on_host = sameOnBothBreaches(*device, *host, w, p);
    ASSERT_TRUE(on_host);
    const auto& from = on_host->source_exemplar;
    EXPECT_GT(std::count(from.begin(), from.end(), 0), 0);  // both exemplars are in the window
    EXPECT_GT(std::count(from.begin(), from.end(), 1), 0);
    p.drainage = Drainage::Off;
    auto off = host->synthesize(w, p);
    ASSERT_TRUE(off) << off.message();
    EXPECT_NE(off.value().heights.heights, on_host->heights.heights);  // the breach did act
}

// orom_norway alone (sea, fjords and lakes: its lowest ground is level water at 0 m), seed 3, over
// `w` with the breach on the host and on the device, which must agree bit for bit.
void norwayOnBothBreaches(const PixelWindow& w, std::shared_ptr<const ExemplarDatabase>* db,
                          std::optional<SynthesisOutput>* on_host) {
    auto loaded = loadOrBuildDatabase({test::sharedExemplarsDir() + "/orom_norway.png"}, DatabaseBuildOptions{},
                                      test::tmpPath("level_ground_norway.tsdb"));
    ASSERT_TRUE(loaded) << loaded.message();
    *db = loaded.value();
    auto device = synthesizerBreachingOn("device", *db), host = synthesizerBreachingOn("host", *db);
    ASSERT_TRUE(device && host);
    SynthesisParams p;
    p.seed = 3;
    *on_host = sameOnBothBreaches(*device, *host, w, p);
    ASSERT_TRUE(*on_host);
}

TEST(DeviceBreach, LevelGroundStaysLevelWithTheSameBitsFromBothBreaches) {
    // orom_norway's sea, fjords and lakes: 8% of it is level ground (synth/level_ground.h). The
    // correction settles copies of it level and the breach leaves it level, with the same bits from
    // the breach on the host and on the device. (The reference backend differs from OpenCL here by
    // a float step in V from level 3 on, before level ground too; with level ground such a step can
    // flip a comparison. SynthesisDifferential holds on the default database.)
    const PixelWindow w{-40, 210, 256, 256};
    std::shared_ptr<const ExemplarDatabase> db;
    std::optional<SynthesisOutput> on_host;
    ASSERT_NO_FATAL_FAILURE(norwayOnBothBreaches(w, &db, &on_host));
    // Of the interior pixels copied from level ground, the share whose slope (central differences)
    // is under 0.5 degrees: in this window 14% before level ground, 38% with it.
    const DatabaseLevel& level0 = db->levels[0];
    const std::vector<uint8_t> flags = synth::levelGroundFlags(level0, synth::LevelGround::tolerance(*db));
    const SynthesisOutput& out = *on_host;
    const double spacing = out.heights.meters_per_pixel_x;
    size_t level_sources = 0, kept_level = 0;
    for (int y = 1; y + 1 < w.height; ++y)
        for (int x = 1; x + 1 < w.width; ++x) {
            const size_t i = static_cast<size_t>(y) * w.width + x;
            const AtlasRect& r = level0.rects[out.source_exemplar[i]];
            const size_t q = static_cast<size_t>(r.y + std::lround(out.source_y[i])) * level0.width + r.x +
                             std::lround(out.source_x[i]);
            if (!flags[q]) continue;
            ++level_sources;
            const double gx = (out.heights.at(x + 1, y) - out.heights.at(x - 1, y)) / (2 * spacing);
            const double gy = (out.heights.at(x, y + 1) - out.heights.at(x, y - 1)) / (2 * spacing);
            kept_level += std::atan(std::hypot(gx, gy)) * 180.0 / M_PI < 0.5;
        }
    const size_t interior = static_cast<size_t>(w.width - 2) * (w.height - 2);
    EXPECT_GT(level_sources, interior / 50) << "the window copies level ground";
    EXPECT_GT(kept_level, level_sources / 4) << kept_level << " of " << level_sources;
}

TEST(DeviceBreach, TheSeaStaysAtSeaLevelAndOnlyCarvedChannelsGoBelowIt) {
    // orom_norway's sea is its lowest ground, at 0 m on 7% of it. Level ground settles to its lowest
    // neighbour, and before the floor (synth/level_ground.h, lowestExemplarHeight) the copied sea
    // sank with its neighbours' offsets: 13.2% of this window under 0 m, none of it at 0 m, down to
    // -523 m in the whole 1024^2. Now only channels carved at coarse levels go under it (0.7%), and
    // most copies of the sea are at sea level exactly, with the same bits from the breach on the host
    // and on the device.
    const PixelWindow w{0, 0, 384, 384};
    std::shared_ptr<const ExemplarDatabase> db;
    std::optional<SynthesisOutput> on_host;
    ASSERT_NO_FATAL_FAILURE(norwayOnBothBreaches(w, &db, &on_host));
    const DatabaseLevel& level0 = db->levels[0];
    const float lowest = synth::lowestExemplarHeight(level0);
    EXPECT_EQ(lowest, 0.0f);  // the sea, as the sidecar's height range says
    const float tolerance = synth::LevelGround::tolerance(*db);
    const std::vector<uint8_t> flags = synth::levelGroundFlags(level0, tolerance);
    const SynthesisOutput& out = *on_host;
    size_t below = 0, sea_sources = 0, at_sea_level = 0;
    for (size_t i = 0; i < out.heights.size(); ++i) {
        below += out.heights.heights[i] < lowest;
        const AtlasRect& r = level0.rects[out.source_exemplar[i]];
        const size_t q = static_cast<size_t>(r.y + std::lround(out.source_y[i])) * level0.width + r.x +
                         std::lround(out.source_x[i]);
        if (!flags[q] || level0.height_m[q] > lowest + tolerance) continue;
        ++sea_sources;
        at_sea_level += out.heights.heights[i] == lowest;
    }
    std::printf("%zu of %zu pixels below %g m; %zu of %zu copies of the sea at sea level\n", below, out.heights.size(),
                lowest, at_sea_level, sea_sources);
    EXPECT_LT(below, out.heights.size() / 50);
    EXPECT_GT(sea_sources, out.heights.size() / 50) << "the window copies the sea";
    EXPECT_GT(at_sea_level, sea_sources / 2);  // none before
}

TEST(DeviceBreach, TheSynthesizerDrainsByDefaultAndOnTheDevice) {
    // The default parameters breach (synthesizer.h): through the OpenCL backend the result equals
    // the explicit setting's and differs from `off`'s. (Both backends: SynthesisDifferential in
    // tests/cl_synthesis_test.cpp.)
    EXPECT_EQ(SynthesisParams{}.drainage, Drainage::Breach);
    auto cl = synthesizerBreachingOn("device");
    ASSERT_TRUE(cl);
    const PixelWindow w{100, -50, 192, 160};
    SynthesisParams defaults, breach, off;
    defaults.seed = breach.seed = off.seed = 21;
    breach.drainage = Drainage::Breach;
    off.drainage = Drainage::Off;
    auto a = cl->synthesize(w, defaults), b = cl->synthesize(w, breach), o = cl->synthesize(w, off);
    ASSERT_TRUE(a && b && o);
    EXPECT_EQ(a.value().heights.heights, b.value().heights.heights);
    EXPECT_NE(a.value().heights.heights, o.value().heights.heights);
}

}  // namespace
}  // namespace terrasynth
