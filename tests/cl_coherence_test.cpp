// Coherence weights, per-pass memory and the freeze brush (paper s5.3).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "terrasynth/synthesizer.h"
#include "test_support.h"

using namespace terrasynth;

namespace {

constexpr int kSize = 384;
const PixelWindow kWindow{0, 0, kSize, kSize};

std::unique_ptr<Synthesizer> make(SynthesisBackend backend) {
    SynthesizerOptions options;
    options.backend = backend;
    auto s = Synthesizer::create(test::defaultDatabase(), options);
    EXPECT_TRUE(s) << s.message();
    return std::move(s.value());
}

Synthesizer& openCl() {
    static std::unique_ptr<Synthesizer> s = make(SynthesisBackend::OpenCL);
    return *s;
}

SynthesisOutput run(Synthesizer& s, const SynthesisParams& p) {
    auto out = s.synthesize(kWindow, p, 0, false);
    EXPECT_TRUE(out) << out.message();
    return std::move(out.value());
}

std::shared_ptr<SynthesisConstraints> pointAt(double x, double y, float height, float radius) {
    auto c = std::make_shared<SynthesisConstraints>();
    c->points.push_back({x, y, height, 0.0f, 0.0f, radius});
    return c;
}

// Free inside the new constraint's reach, Coherent elsewhere, Frozen in `frozen` (x0,y0,x1,y1).
std::shared_ptr<CoherenceMap> weights(double cx, double cy, double radius, const int frozen[4] = nullptr) {
    auto map = std::make_shared<CoherenceMap>();
    map->width = map->height = kSize;
    map->weights.assign(kSize * kSize, Coherence::Coherent);
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            Coherence& w = map->weights[y * kSize + x];
            if (std::hypot(x - cx, y - cy) < radius) w = Coherence::Free;
            if (frozen && x >= frozen[0] && x < frozen[2] && y >= frozen[1] && y < frozen[3]) w = Coherence::Frozen;
        }
    return map;
}

}  // namespace

TEST(Coherence, ResynthesisWithUnchangedInputsIsIdentical) {
    SynthesisParams p;
    p.seed = 3;
    p.record_history = true;
    const auto first = run(openCl(), p);
    ASSERT_TRUE(first.history);
    std::printf("history: %.1f bytes per output pixel\n", double(first.history->memoryBytes()) / (kSize * kSize));
    p.previous = first.history;
    p.coherence = weights(200, 200, 64);  // Free somewhere, Coherent elsewhere: nothing changed, nothing moves
    const auto again = run(openCl(), p);
    EXPECT_EQ(0, std::memcmp(first.heights.heights.data(), again.heights.heights.data(), kSize * kSize * 4));
}

TEST(Coherence, NewConstraintChangesLittleOutsideItsReach) {
    SynthesisParams p;
    p.seed = 4;
    p.record_history = true;
    const auto before = run(openCl(), p);
    const double cx = 190, cy = 200, radius = 64;
    const float target = before.heights.at(190, 200) + 600.0f;

    auto changedOutside = [&](const SynthesisOutput& after) {
        size_t outside = 0, changed = 0;
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x) {
                if (std::hypot(x - cx, y - cy) < radius) continue;
                ++outside;
                changed += std::fabs(after.heights.at(x, y) - before.heights.at(x, y)) > 1.0f;
            }
        return double(changed) / outside;
    };
    SynthesisParams edited = p;
    edited.constraints = pointAt(cx, cy, target, radius);
    const double without = changedOutside(run(openCl(), edited));
    edited.previous = before.history;
    edited.coherence = weights(cx, cy, radius);
    const auto after = run(openCl(), edited);
    const double with = changedOutside(after);
    std::printf("pixels outside the reach changing by > 1 m: %.2f%% without coherence, %.2f%% with\n", 100 * without,
                100 * with);
    EXPECT_LT(with, 0.02);
    EXPECT_LT(with, without);
    // The constraint still acts inside its reach.
    EXPECT_LT(std::fabs(after.heights.at(190, 200) - target), std::fabs(before.heights.at(190, 200) - target) * 0.5f);
}

TEST(Coherence, FrozenPixelsAreBitIdenticalAcrossEdits) {
    SynthesisParams p;
    p.seed = 6;
    p.record_history = true;
    const auto before = run(openCl(), p);
    const int frozen[4] = {40, 40, 180, 180};
    SynthesisParams edited = p;
    edited.constraints = pointAt(200, 200, before.heights.at(200, 200) - 500.0f, 90.0f);  // reaches into the frozen box
    edited.previous = before.history;
    edited.coherence = weights(200, 200, 90, frozen);
    const auto after = run(openCl(), edited);
    size_t different = 0, changed_elsewhere = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const bool inside = x >= frozen[0] && x < frozen[2] && y >= frozen[1] && y < frozen[3];
            const bool same = after.heights.at(x, y) == before.heights.at(x, y);
            if (inside) different += !same;
            else changed_elsewhere += !same;
        }
    EXPECT_EQ(different, 0u);
    EXPECT_GT(changed_elsewhere, 100u);  // the edit did act outside the frozen box
}

TEST(Coherence, OpenClMatchesReference) {
    static std::unique_ptr<Synthesizer> ref = make(SynthesisBackend::Reference);
    SynthesisParams p;
    p.seed = 8;
    p.record_history = true;
    const PixelWindow w{0, 0, 160, 128};
    auto a = openCl().synthesize(w, p, 0, false);
    ASSERT_TRUE(a);
    SynthesisParams edited = p;
    edited.constraints = pointAt(80, 60, a->heights.at(80, 60) + 300.0f, 40.0f);
    edited.previous = a->history;
    auto map = std::make_shared<CoherenceMap>();
    map->width = 160, map->height = 128;
    map->weights.assign(160 * 128, Coherence::Coherent);
    for (int y = 0; y < 30; ++y)
        for (int x = 0; x < 50; ++x) map->weights[y * 160 + x] = Coherence::Frozen;
    edited.coherence = map;
    auto cl = openCl().synthesize(w, edited, 0, false), rf = ref->synthesize(w, edited, 0, false);
    ASSERT_TRUE(cl) << cl.message();
    ASSERT_TRUE(rf) << rf.message();
    size_t off = 0;
    for (size_t i = 0; i < cl->heights.size(); ++i) off += std::fabs(cl->heights.heights[i] - rf->heights.heights[i]) > 1e-3f;
    EXPECT_LE(off, cl->heights.size() / 1000);
}
