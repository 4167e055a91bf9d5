// The reference backend: runs the C++ reference kernels through the shared driver.
#include "synth/reference_synthesizer.h"

#include <cmath>
#include <utility>

#include "synth/initial_patches.h"
#include "synth/level_ground.h"
#include "synth/reference_kernels.h"
#include "synth/synthesis_driver.h"

namespace terrasynth::synth {
namespace {

class ReferenceSteps final : public SynthesisSteps {
public:
    ReferenceSteps(const ExemplarDatabase& db, DepthMargins& margins, LevelGround& level_ground)
        : db_(db), margins_(margins), level_ground_(level_ground) {}
    Status init(int level, const LevelRegion& region, uint32_t seed) override {
        auto entry = startingEntryLevels(db_, level);
        if (!entry) return entry.status();
        entry_levels_ = std::move(entry.value());
        const ShareLayout layout = shareLayout(db_, entry_levels_, level, region.x, region.y, region.width, region.height, seed);
        layout_ = layout.exemplar;
        coarsest_ = level;
        referencePatches(db_.levels[level], layout, region, seed, level, false, current_);
        return Status::ok();
    }
    Status upsample(int level, const LevelRegion& parent, const LevelRegion& child, float jitter, uint32_t seed,
                    const TypePaint* paint) override {
        std::vector<PixelState> next;
        referenceUpsample(db_.levels[level + 1], db_.levels[level], parent, current_, child, jitter, seed, level, next);
        current_.swap(next);
        if (entersAt(entry_levels_, level))
            referencePatches(db_.levels[level], entryLayout(db_, entry_levels_, level, child, seed, paint), child, seed,
                             level, true, current_);
        return Status::ok();
    }
    Status beginLevel(int level, const LevelRegion&, const constraints::LevelConstraints& constraints,
                      const std::vector<uint8_t>& coherence, uint32_t seed) override {
        context_.coherence = coherence;
        context_.level = level;
        context_.meters_per_pixel0 = static_cast<float>(db_.meters_per_pixel);
        context_.seed_salt = seedingSalt(seed, level);
        context_.constraints = constraints;
        context_.seeds = seedTable(db_.levels[level]);
        context_.layout = level == coarsest_ ? layout_ : std::vector<uint8_t>{};
        context_.level_ground = &levelGround(level);
        context_.level_tolerance = LevelGround::tolerance(db_);
        context_.lowest_height = level_ground_.lowest(db_, level);
        return Status::ok();
    }
    Status beginPass(int, const LevelRegion&, const PassHistory& previous) override {
        context_.previous = previous;
        return Status::ok();
    }
    Status recordPass(int level, const LevelRegion&, SynthesisHistory::Pass& out) override {
        const int width = db_.levels[level].width;
        out.index.resize(current_.size());
        out.v.resize(current_.size());
        for (size_t i = 0; i < current_.size(); ++i) {
            out.index[i] = static_cast<uint32_t>(std::lround(current_[i].y)) * static_cast<uint32_t>(width) +
                           static_cast<uint32_t>(std::lround(current_[i].x));
            out.v[i] = current_[i].v;
        }
        return Status::ok();
    }
    Status correct(int level, const LevelRegion& region, int px, int py, int inset) override {
        referenceCorrect(db_.levels[level], region, px, py, inset, context_, current_);
        return Status::ok();
    }
    Status previewLevel(int level, const LevelRegion& region, const std::vector<uint8_t>& coherence,
                        const PassHistory& previous) override {
        referencePreviewLevel(db_.levels[level], region, coherence, previous, current_.data());
        return Status::ok();
    }
    float depthMargin(int level) override { return margins_.at(db_, level); }
    const std::vector<uint8_t>& basinExemplars() override { return margins_.basinExemplars(db_); }
    const std::vector<uint8_t>& levelGround(int level) override { return level_ground_.flags(db_, level); }
    Status relax(int level, const LevelRegion& region, int iterations, const RelaxationInputs& inputs) override {
        relaxOffsets(db_.levels[level], region, db_.meters_per_pixel * std::ldexp(1.0, level), iterations, inputs,
                     current_.data());
        return Status::ok();
    }
    Status drain(int level, const LevelRegion& region, int radius, const DrainageInputs& inputs) override {
        breachPits(db_.levels[level], region, radius, inputs, current_.data());
        return Status::ok();
    }
    Status resolve(int level, const LevelRegion& region, const LevelRegion& out, SynthesisOutput& output,
                   bool want_sources) override {
        referenceResolve(db_.levels[level], region, current_, out, output.heights.heights.data(),
                         want_sources ? output.source_x.data() : nullptr, want_sources ? output.source_y.data() : nullptr,
                         want_sources ? output.source_exemplar.data() : nullptr);
        return Status::ok();
    }

private:
    const ExemplarDatabase& db_;
    DepthMargins& margins_;
    LevelGround& level_ground_;
    std::vector<int> entry_levels_;  // entryLevels of the current synthesis
    int coarsest_ = -1;              // its coarsest level, whose passes hold layout_
    std::vector<uint8_t> layout_;    // shareLayout exemplars of the coarsest level's region
    std::vector<PixelState> current_;
    CorrectionContext context_;
};

class ReferenceSynthesizer final : public Synthesizer {
public:
    explicit ReferenceSynthesizer(std::shared_ptr<const ExemplarDatabase> db) : Synthesizer(std::move(db)) {}
    Result<SynthesisOutput> synthesize(const PixelWindow& window, const SynthesisParams& params, int output_level,
                                       bool want_sources) override {
        ReferenceSteps steps(*db_, margins_, level_ground_);
        size_t peak = 0;
        auto out = runSynthesis(*db_, window, params, output_level, want_sources, steps, stop_requested_, &peak);
        if (out) bytes_per_pixel_ = static_cast<double>(peak * sizeof(PixelState)) / (window.width * window.height) +
                                    (want_sources ? 13.0 : 4.0);
        return out;
    }
    std::string deviceName() const override { return "reference C++"; }
    double lastBytesPerPixel() const override { return bytes_per_pixel_; }

private:
    double bytes_per_pixel_ = 0.0;
    DepthMargins margins_;
    LevelGround level_ground_;
};

}  // namespace

std::unique_ptr<Synthesizer> createReferenceSynthesizer(std::shared_ptr<const ExemplarDatabase> db) {
    return std::make_unique<ReferenceSynthesizer>(std::move(db));
}

}  // namespace terrasynth::synth
