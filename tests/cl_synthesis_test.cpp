// Synthesis core (paper s4) through the OpenCL backend on PoCL, against the C++ reference, and the
// windowed-determinism contract of terrasynth/synthesizer.h.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>

#include "terrasynth/synthesizer.h"
#include "test_support.h"

using namespace terrasynth;

namespace {

std::unique_ptr<Synthesizer> makeSynthesizer(SynthesisBackend backend) {
    SynthesizerOptions options;
    options.backend = backend;
    auto s = Synthesizer::create(test::defaultDatabase(), options);
    EXPECT_TRUE(s) << s.message();
    return std::move(s.value());  // without a device: stops here with the error, not on a null synthesizer
}

Synthesizer& openCl() {
    static std::unique_ptr<Synthesizer> s = makeSynthesizer(SynthesisBackend::OpenCL);
    return *s;
}
Synthesizer& reference() {
    static std::unique_ptr<Synthesizer> s = makeSynthesizer(SynthesisBackend::Reference);
    return *s;
}

SynthesisOutput run(Synthesizer& s, PixelWindow w, uint32_t seed = 7, int level = 0, bool sources = false,
                    int passes = 2, Drainage drainage = Drainage::Off) {
    SynthesisParams p;
    p.seed = seed;
    p.correction_passes = passes;
    p.drainage = drainage;
    auto out = s.synthesize(w, p, level, sources);
    EXPECT_TRUE(out) << out.message();
    return out ? std::move(out.value()) : SynthesisOutput{};
}

bool sameBits(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

// `point`, and type 1 painted over [x0, x1) x [y0, y1) of a width x height painting at the origin
// (unpainted elsewhere).
std::shared_ptr<SynthesisConstraints> pointAndPaintedRectangle(const PointConstraint& point, int width, int height,
                                                              int x0, int x1, int y0, int y1) {
    auto constraints = std::make_shared<SynthesisConstraints>();
    constraints->points.push_back(point);
    TypePaint& paint = constraints->types;
    paint.x = 0, paint.y = 0, paint.width = width, paint.height = height;
    paint.types.assign(static_cast<size_t>(width) * height, TypePaint::kUnpainted);
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) paint.types[static_cast<size_t>(y) * width + x] = 1;
    return constraints;
}

}  // namespace

TEST(Synthesis, SameSeedSameBitsDifferentSeedDifferentTerrain) {
    const PixelWindow w{0, 0, 256, 256};
    const auto a = run(openCl(), w, 11), b = run(openCl(), w, 11), c = run(openCl(), w, 12);
    EXPECT_TRUE(sameBits(a.heights.heights, b.heights.heights));
    size_t differing = 0;
    for (size_t i = 0; i < a.heights.size(); ++i) differing += a.heights.heights[i] != c.heights.heights[i];
    EXPECT_GT(differing, a.heights.size() / 2);
}

TEST(Synthesis, AdjacentWindowsEqualHalvesOfTheWholeWindow) {
    const auto whole = run(openCl(), {0, 0, 512, 256});
    const auto left = run(openCl(), {0, 0, 256, 256});
    const auto right = run(openCl(), {256, 0, 256, 256});
    for (int y = 0; y < 256; ++y)
        for (int x = 0; x < 256; ++x) {
            ASSERT_EQ(left.heights.at(x, y), whole.heights.at(x, y)) << x << "," << y;
            ASSERT_EQ(right.heights.at(x, y), whole.heights.at(x + 256, y)) << x + 256 << "," << y;
        }
}

TEST(Synthesis, AnyWindowIncludingNegativeCoordinatesMatchesTheWhole) {
    const auto whole = run(openCl(), {-300, -170, 400, 300}, 3, 0, true);
    const auto part = run(openCl(), {-123, -77, 97, 131}, 3, 0, true);
    for (int y = 0; y < part.heights.height; ++y)
        for (int x = 0; x < part.heights.width; ++x) {
            const int wx = x + 177, wy = y + 93;
            ASSERT_EQ(part.heights.at(x, y), whole.heights.at(wx, wy));
            ASSERT_EQ(part.source_exemplar[y * 97 + x], whole.source_exemplar[wy * 400 + wx]);
        }
}

TEST(Synthesis, DrainedWindowsMatchTheWholeAndChangeTheTerrain) {
    // Issue 17: breaching reads 2 * breachRadius + 1 pixels around each pixel per level, which the
    // window plan adds to the margins, so windows still agree bit for bit with a larger window.
    const auto whole = run(openCl(), {-300, -170, 400, 300}, 3, 0, false, 2, Drainage::Breach);
    const auto part = run(openCl(), {-123, -77, 97, 131}, 3, 0, false, 2, Drainage::Breach);
    for (int y = 0; y < part.heights.height; ++y)
        for (int x = 0; x < part.heights.width; ++x) ASSERT_EQ(part.heights.at(x, y), whole.heights.at(x + 177, y + 93));
    const auto undrained = run(openCl(), {-300, -170, 400, 300}, 3);
    EXPECT_FALSE(sameBits(whole.heights.heights, undrained.heights.heights));
}

TEST(Synthesis, CoarseOutputLevelsAreWindowedToo) {
    const auto whole = run(openCl(), {-64, 0, 128, 64}, 5, 3);
    const auto part = run(openCl(), {0, 0, 64, 64}, 5, 3);
    EXPECT_NEAR(whole.heights.meters_per_pixel_x, test::defaultDatabase()->meters_per_pixel * 8, 1e-9);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) ASSERT_EQ(part.heights.at(x, y), whole.heights.at(x + 64, y));
}

TEST(Synthesis, TheFinestLevelsAreUpsampledWithoutJitter) {
    // With no correction passes a level is its parent upsampled (eq. 1-2): child = 2 * parent +
    // (x & 1, y & 1), plus eq. 1's jitter. Levels 0-1 take none (synthesis_driver.h,
    // kUnjitteredLevels), level 2 the default 0.4 px: level 2 must differ from its upsampled
    // parent, levels 1 and 0 must not. Sources are exemplar pixels of their own level, so the
    // relation is exact.
    for (Synthesizer* s : {&openCl(), &reference()}) {
        const int side = 16;
        std::vector<SynthesisOutput> levels;  // levels[k]: level k of the same ground
        for (int level = 0; level <= 3; ++level) {
            const int scale = 8 >> level;
            levels.push_back(run(*s, {-2 * scale, 3 * scale, side * scale, side * scale}, 5, level, true, 0));
        }
        auto followsParent = [&](int level) {
            const SynthesisOutput &child = levels[level], &parent = levels[level + 1];
            const int child_side = side * (8 >> level);
            size_t exact = 0;
            for (int y = 0; y < child_side; ++y)
                for (int x = 0; x < child_side; ++x) {
                    const size_t c = static_cast<size_t>(y) * child_side + x, p = static_cast<size_t>(y / 2) * (child_side / 2) + x / 2;
                    exact += child.source_exemplar[c] == parent.source_exemplar[p] &&
                             child.source_x[c] == 2.0f * parent.source_x[p] + static_cast<float>(x & 1) &&
                             child.source_y[c] == 2.0f * parent.source_y[p] + static_cast<float>(y & 1);
                }
            return static_cast<double>(exact) / (static_cast<double>(child_side) * child_side);
        };
        const double level2 = followsParent(2), level1 = followsParent(1), level0 = followsParent(0);
        std::printf("%s: exactly the upsampled parent at %.1f%% of level 2's pixels, %.1f%% of level 1's, %.1f%% of level 0's\n",
                    s == &openCl() ? "OpenCL" : "reference", 100 * level2, 100 * level1, 100 * level0);
        EXPECT_LT(level2, 0.05);
        EXPECT_GE(level1, 0.99);  // a parent at an exemplar's interior margin may clamp a child
        EXPECT_GE(level0, 0.99);
    }
}

TEST(SynthesisDifferential, OpenClMatchesReferenceWithoutCorrection) {
    // Init + upsample/jitter + resolve only. Tolerances: coordinates within 1e-3 pixel (a few float
    // ulps at atlas coordinates of ~1000) and heights
    // within 1 cm; the kernel compiler may still fuse a multiply-add the C++ side rounds twice.
    const PixelWindow w{-40, 25, 160, 120};
    const auto cl = run(openCl(), w, 9, 0, true, 0), ref = run(reference(), w, 9, 0, true, 0);
    float worst_coordinate = 0.0f, worst_height = 0.0f;
    for (size_t i = 0; i < cl.heights.size(); ++i) {
        worst_coordinate = std::max({worst_coordinate, std::fabs(cl.source_x[i] - ref.source_x[i]),
                                     std::fabs(cl.source_y[i] - ref.source_y[i])});
        worst_height = std::max(worst_height, std::fabs(cl.heights.heights[i] - ref.heights.heights[i]));
    }
    std::printf("worst coordinate difference %g px, worst height difference %g m\n", worst_coordinate, worst_height);
    EXPECT_LE(worst_coordinate, 1e-3f);
    EXPECT_LE(worst_height, 1e-2f);
    EXPECT_EQ(cl.source_exemplar, ref.source_exemplar);
}

TEST(SynthesisDifferential, OpenClMatchesReferenceWithCorrection) {
    // Tolerance: identical float operations in identical order (FP_CONTRACT OFF on both sides);
    // we allow 0.1% of pixels to differ by more than 1 mm in case a driver rounds a builtin
    // differently and flips an argmin, which then changes a small patch.
    const PixelWindow w{100, -50, 192, 160};
    const auto cl = run(openCl(), w, 21, 0, true), ref = run(reference(), w, 21, 0, true);
    size_t off = 0;
    for (size_t i = 0; i < cl.heights.size(); ++i) off += std::fabs(cl.heights.heights[i] - ref.heights.heights[i]) > 1e-3f;
    std::printf("pixels differing by more than 1 mm: %zu of %zu\n", off, cl.heights.size());
    EXPECT_LE(off, cl.heights.size() / 1000);
}

TEST(SynthesisDifferential, OpenClMatchesReferenceWithDrainage) {
    // Both backends breach on the host with the same code (drainage_breach.h); the tolerance is that
    // of the correction differential above.
    const PixelWindow w{100, -50, 192, 160};
    const auto cl = run(openCl(), w, 21, 0, false, 2, Drainage::Breach), ref = run(reference(), w, 21, 0, false, 2, Drainage::Breach);
    size_t off = 0;
    for (size_t i = 0; i < cl.heights.size(); ++i) off += std::fabs(cl.heights.heights[i] - ref.heights.heights[i]) > 1e-3f;
    std::printf("pixels differing by more than 1 mm: %zu of %zu\n", off, cl.heights.size());
    EXPECT_LE(off, cl.heights.size() / 1000);
}

TEST(Synthesis, HeightsAreFiniteAndWithinTheExemplarsRange) {
    const auto out = run(openCl(), {0, 0, 512, 512}, 4, 0, true);
    float lo = 1e9f, hi = -1e9f;
    for (float h : out.heights.heights) {
        ASSERT_TRUE(std::isfinite(h));
        lo = std::min(lo, h), hi = std::max(hi, h);
    }
    std::printf("synthesized 512^2 range %.1f .. %.1f m\n", lo, hi);
    // Offsets V can move exemplar terrain up or down, but not to absurd altitudes.
    EXPECT_GT(lo, -3000.0f);
    EXPECT_LT(hi, 12000.0f);
    EXPECT_GT(hi - lo, 300.0f);  // a real relief, not a flat plate
    // Every source coordinate lies inside its exemplar.
    const DatabaseLevel& l0 = test::defaultDatabase()->levels[0];
    for (size_t i = 0; i < out.source_x.size(); ++i) {
        const AtlasRect& r = l0.rects[out.source_exemplar[i]];
        ASSERT_GE(out.source_x[i], 0.0f);
        ASSERT_LE(out.source_x[i], r.width - 1.0f);
        ASSERT_GE(out.source_y[i], 0.0f);
        ASSERT_LE(out.source_y[i], r.height - 1.0f);
    }
}

TEST(Synthesis, RejectsAbsurdRequestsWithClearErrors) {
    SynthesisParams p;
    auto huge = openCl().synthesize({0, 0, 100000, 10}, p, 0, false);
    ASSERT_FALSE(huge);
    EXPECT_NE(huge.message().find("window size"), std::string::npos);
    p.jitter = 5.0f;
    auto jitter = openCl().synthesize({0, 0, 10, 10}, p, 0, false);
    ASSERT_FALSE(jitter);
    EXPECT_NE(jitter.message().find("jitter"), std::string::npos);
    p.jitter = 0.4f;
    auto level = openCl().synthesize({0, 0, 10, 10}, p, 9, false);
    ASSERT_FALSE(level);
    EXPECT_NE(level.message().find("output level"), std::string::npos);
}

TEST(Synthesis, MissingOpenClDeviceIsAClearError) {
    SynthesizerOptions options;
    options.device = "no-such-device-xyz";
    auto s = Synthesizer::create(test::defaultDatabase(), options);
    ASSERT_FALSE(s);
    EXPECT_NE(s.message().find("no device matches"), std::string::npos) << s.message();
}

TEST(SynthesisDifferential, OpenClMatchesReferenceWithConstraints) {
    // Point constraints and type painting go through the same kernels; same tolerance as above.
    const auto constraints = pointAndPaintedRectangle({120.0, 90.0, 4000.0f, 45.0f, 20.0f, 80.0f}, 200, 160, 0, 200, 20, 60);
    SynthesisParams p;
    p.seed = 5;
    p.constraints = constraints;
    const PixelWindow w{0, 0, 200, 160};
    auto cl = openCl().synthesize(w, p, 0, true);
    auto ref = reference().synthesize(w, p, 0, true);
    ASSERT_TRUE(cl) << cl.message();
    ASSERT_TRUE(ref) << ref.message();
    size_t off = 0;
    for (size_t i = 0; i < cl->heights.size(); ++i) off += std::fabs(cl->heights.heights[i] - ref->heights.heights[i]) > 1e-3f;
    std::printf("with constraints: pixels differing by more than 1 mm: %zu of %zu\n", off, cl->heights.size());
    EXPECT_LE(off, cl->heights.size() / 1000);
    // And the constraint did something: the unconstrained terrain differs.
    SynthesisParams free = p;
    free.constraints.reset();
    auto plain = openCl().synthesize(w, free, 0, false);
    ASSERT_TRUE(plain);
    EXPECT_NE(plain->heights.heights, cl->heights.heights);
}

// The candidate prefetch (kernels/synthesis.cl, TS_CPU_PREFETCH: on for CPU devices, what a GPU
// runs without) reorders loads only: with it and without, the same bits, painted types (rejected
// candidates, seeding) and points included, with the default drainage.
TEST(Synthesis, CandidatePrefetchChangesNoBit) {
    auto synthesizerWithPrefetch = [](const char* setting) {
        ::setenv("TERRASYNTH_CL_PREFETCH", setting, 1);
        auto s = Synthesizer::create(test::defaultDatabase());
        ::unsetenv("TERRASYNTH_CL_PREFETCH");
        EXPECT_TRUE(s) << s.message();
        return s ? std::move(s.value()) : nullptr;
    };
    auto with = synthesizerWithPrefetch("on"), without = synthesizerWithPrefetch("off");
    ASSERT_TRUE(with && without);
    const auto constraints = pointAndPaintedRectangle({150.0, 80.0, 3500.0f, 30.0f, 24.0f, 200.0f}, 256, 192, 20, 240, 100, 160);
    SynthesisParams plain, constrained;
    plain.seed = constrained.seed = 13;
    constrained.constraints = constraints;
    for (const SynthesisParams& p : {plain, constrained}) {
        const PixelWindow w{-60, 30, 256, 192};
        auto a = with->synthesize(w, p, 0, true), b = without->synthesize(w, p, 0, true);
        ASSERT_TRUE(a) << a.message();
        ASSERT_TRUE(b) << b.message();
        EXPECT_TRUE(sameBits(a->heights.heights, b->heights.heights));
        EXPECT_TRUE(sameBits(a->source_x, b->source_x));
        EXPECT_TRUE(sameBits(a->source_y, b->source_y));
        EXPECT_EQ(a->source_exemplar, b->source_exemplar);
    }
}

// Huge pages for a CPU device's large buffers (cl::HostMemory: 2 MiB pages of the host's, advised
// before the database is copied in and before a state is first written, as the buffers' storage)
// change where the bytes live, not what they are: the same bits with them and without, for a
// window whose level-0 states pass kHugePageAdviceBytes (about 7 MB) and a small one (under it).
TEST(Synthesis, HugePagesChangeNoBit) {
    auto synthesizerWithHugePages = [](const char* setting) {
        ::setenv("TERRASYNTH_CL_HUGE_PAGES", setting, 1);
        auto s = Synthesizer::create(test::defaultDatabase());
        ::unsetenv("TERRASYNTH_CL_HUGE_PAGES");
        EXPECT_TRUE(s) << s.message();
        return s ? std::move(s.value()) : nullptr;
    };
    auto with = synthesizerWithHugePages("on"), without = synthesizerWithHugePages("off");
    ASSERT_TRUE(with && without);
    SynthesisParams p;
    p.seed = 17;
    for (const PixelWindow& w : {PixelWindow{-300, 140, 640, 512}, PixelWindow{700, -20, 96, 64}}) {
        auto a = with->synthesize(w, p, 0, true), b = without->synthesize(w, p, 0, true);
        ASSERT_TRUE(a) << a.message();
        ASSERT_TRUE(b) << b.message();
        EXPECT_TRUE(sameBits(a->heights.heights, b->heights.heights));
        EXPECT_TRUE(sameBits(a->source_x, b->source_x));
        EXPECT_EQ(a->source_exemplar, b->source_exemplar);
    }
}

TEST(Synthesis, APreviewLevelKeepsWhatIsNotFreeAndUpsamplesTheFreeArea) {
    // SynthesisParams::preview_levels (an editor's drag step): against a previous synthesis of the
    // same window, the finest level keeps every pixel that is not Free bit for bit and leaves the
    // Free ones upsampled and jittered, uncorrected; both backends agree within the correction
    // differential's tolerance, and the history holds that state for every pass.
    const PixelWindow w{100, -50, 192, 160};
    const PixelWindow free_area{148, -10, 96, 80};
    SynthesisParams p;
    p.seed = 21;
    p.record_history = true;
    auto full = openCl().synthesize(w, p, 0, false);
    ASSERT_TRUE(full) << full.message();
    auto map = std::make_shared<CoherenceMap>();
    map->x = w.x, map->y = w.y, map->width = w.width, map->height = w.height;
    map->weights.assign(static_cast<size_t>(w.width) * w.height, Coherence::Coherent);
    auto inside = [&](int x, int y) {
        return w.x + x >= free_area.x && w.x + x < free_area.x + free_area.width && w.y + y >= free_area.y &&
               w.y + y < free_area.y + free_area.height;
    };
    for (int y = 0; y < w.height; ++y)
        for (int x = 0; x < w.width; ++x)
            if (inside(x, y)) map->weights[static_cast<size_t>(y) * w.width + x] = Coherence::Free;
    SynthesisParams preview = p;
    preview.previous = full->history;
    preview.coherence = map;
    preview.preview_levels = 1;
    auto cl = openCl().synthesize(w, preview, 0, false);
    auto ref = reference().synthesize(w, preview, 0, false);
    ASSERT_TRUE(cl) << cl.message();
    ASSERT_TRUE(ref) << ref.message();
    size_t kept_changed = 0, free_pixels = 0, free_changed = 0, off = 0;
    for (int y = 0; y < w.height; ++y)
        for (int x = 0; x < w.width; ++x) {
            const float before = full->heights.at(x, y), now = cl->heights.at(x, y);
            if (inside(x, y)) {
                ++free_pixels;
                free_changed += now != before;
            } else {
                kept_changed += std::memcmp(&now, &before, sizeof(float)) != 0;
            }
            off += std::fabs(now - ref->heights.at(x, y)) > 1e-3f;
        }
    std::printf("preview: %zu of %zu free pixels changed, %zu kept pixels changed; backends differ > 1 mm at %zu\n",
                free_changed, free_pixels, kept_changed, off);
    EXPECT_EQ(kept_changed, 0u);
    EXPECT_GT(free_changed, free_pixels * 9 / 10) << "the free area was not re-synthesized";
    EXPECT_LE(off, cl->heights.size() / 1000);
    const auto& level0 = cl->history->levels[0];
    ASSERT_EQ(level0.passes.size(), full->history->levels[0].passes.size());
    for (const auto& pass : level0.passes) EXPECT_EQ(pass.index, level0.passes[0].index);
    // Without a preview the same request corrects the free area: a different terrain there.
    preview.preview_levels = 0;
    auto corrected = openCl().synthesize(w, preview, 0, false);
    ASSERT_TRUE(corrected);
    EXPECT_NE(corrected->heights.heights, cl->heights.heights);
}

// SynthesizerOptions::stop_requested: asked once before each synthesized level on both backends; a
// request stops the call with kSynthesisStopped, and the same synthesizer then synthesizes the same
// bits as one that was never asked to stop.
TEST(Synthesis, AStopRequestEndsTheCallBetweenLevelsAndChangesNothingAfter) {
    const PixelWindow w{-20, 30, 48, 40};
    SynthesisParams p;
    p.seed = 11;
    const int levels = coarsestSynthesizedLevel(*test::defaultDatabase(), p) + 1;
    for (SynthesisBackend backend : {SynthesisBackend::Reference, SynthesisBackend::OpenCL}) {
        int asked = 0, stop_at = 0;  // stop on the stop_at-th question; 0 = never
        SynthesizerOptions options;
        options.backend = backend;
        options.stop_requested = [&] { return ++asked == stop_at; };
        auto s = Synthesizer::create(test::defaultDatabase(), options);
        ASSERT_TRUE(s) << s.message();
        auto whole = s.value()->synthesize(w, p, 0, false);
        ASSERT_TRUE(whole) << whole.message();
        EXPECT_EQ(asked, levels);
        for (int stop : {1, 2, levels}) {
            asked = 0, stop_at = stop;
            auto stopped = s.value()->synthesize(w, p, 0, false);
            ASSERT_FALSE(stopped);
            EXPECT_EQ(stopped.message(), kSynthesisStopped);
            EXPECT_EQ(asked, stop);
        }
        asked = 0, stop_at = 0;
        auto again = s.value()->synthesize(w, p, 0, false);
        ASSERT_TRUE(again) << again.message();
        EXPECT_TRUE(sameBits(again->heights.heights, whole->heights.heights));
        Synthesizer& unasked = backend == SynthesisBackend::Reference ? reference() : openCl();
        EXPECT_TRUE(sameBits(whole->heights.heights, run(unasked, w, 11, 0, false, 2, Drainage::Breach).heights.heights));
    }
}
