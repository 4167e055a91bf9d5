#include "synth/synthesis_driver.h"

#include "constraints/curve_field.h"
#include "terrasynth/limits.h"

#include <algorithm>
#include <cmath>

#include "synth/initial_patches.h"
#include "synth/level_ground.h"

namespace terrasynth::synth {

int coarsestLevel(const ExemplarDatabase& db, const SynthesisParams& params) {
    return params.coarsest_level < 0 ? automaticCoarsestLevel(db) : params.coarsest_level;
}

Status validateRequest(const ExemplarDatabase& db, const PixelWindow& window, const SynthesisParams& params,
                       int output_level) {
    if (db.levels.empty()) return Status::error("database has no levels");
    if (!(params.jitter >= 0.0f && params.jitter <= 1.0f)) return Status::error("jitter must be in [0, 1]");
    if (params.correction_passes < 0 || params.correction_passes > 4)
        return Status::error("correction_passes must be 0..4");
    const int coarsest = coarsestLevel(db, params);
    if (coarsest < 0 || coarsest >= db.levelCount())
        return Status::error("coarsest_level must be -1 or 0.." + std::to_string(db.levelCount() - 1));
    // Above the coarsest synthesized level the output is a block average of it (synthesis_driver.h).
    const int highest = params.coarsest_level < 0 ? db.levelCount() - 1 : coarsest;
    if (output_level < 0 || output_level > highest)
        return Status::error("output level must be 0.." + std::to_string(highest));
    if (window.width < 1 || window.height < 1 || window.width > 16384 || window.height > 16384)
        return Status::error("window size must be 1..16384 per side, got " + std::to_string(window.width) + "x" +
                             std::to_string(window.height));
    const int above = std::max(0, output_level - coarsest);
    if ((static_cast<int64_t>(window.width) << above) > 16384 || (static_cast<int64_t>(window.height) << above) > 16384)
        return Status::error("window of " + std::to_string(window.width) + "x" + std::to_string(window.height) +
                             " at level " + std::to_string(output_level) + " covers more than 16384 pixels per side of level " +
                             std::to_string(coarsest) + ", the coarsest synthesized");
    // Compared without negating: -INT64_MIN does not exist.
    if (window.x < -kMaxGlobalCoordinate || window.x > kMaxGlobalCoordinate || window.y < -kMaxGlobalCoordinate ||
        window.y > kMaxGlobalCoordinate)
        return Status::error("window origin beyond +-2^29 pixels");
    if (params.preview_levels < 0 || params.preview_levels > 16) return Status::error("preview_levels must be 0..16");
    if (params.first_constrained_level < 0 || params.first_constrained_level > 12)
        return Status::error("first_constrained_level must be 0..12");
    if (params.constraints) {
        const SynthesisConstraints& c = *params.constraints;
        if (c.points.size() > static_cast<size_t>(limits::kMaxPointConstraints))
            return Status::error("constraints: " + std::to_string(c.points.size()) + " point constraints, at most " +
                                 std::to_string(limits::kMaxPointConstraints));
        const double bound = static_cast<double>(kMaxGlobalCoordinate);
        for (size_t i = 0; i < c.points.size(); ++i) {
            const PointConstraint& p = c.points[i];
            if (!(p.radius_px > 0.0f && p.radius_px <= 1e6f) || !std::isfinite(p.height_m) || !std::isfinite(p.lift_m) ||
                !std::isfinite(p.tilt_east) || !std::isfinite(p.tilt_south) || !std::isfinite(p.wide_tilt_east) ||
                !std::isfinite(p.wide_tilt_south) ||
                !(p.slope_angle_deg >= 0.0f && p.slope_angle_deg <= 80.0f) || !std::isfinite(p.slope_direction_deg) ||
                !(std::fabs(p.x) <= bound && std::fabs(p.y) <= bound))
                return Status::error("point constraint " + std::to_string(i) +
                                     ": site within +-2^29 pixels, radius in (0, 1e6], height and lifts finite, slope angle "
                                     "0..80 degrees");
        }
        if (Status s = constraints::checkCurveLimits(c.curves, "constraints.curves"); !s) return s;
        for (size_t i = 0; i < c.curves.size(); ++i)
            for (float lift : c.curves[i].lift_m)
                if (!std::isfinite(lift)) return Status::error("curve constraint " + std::to_string(i) + ": lift must be finite");
        if (c.types.types.size() != static_cast<size_t>(std::max(0, c.types.width)) * std::max(0, c.types.height))
            return Status::error("constraints: type painting size does not match its rectangle");
        if (!params.constraints->types.empty() && db.type_names.size() > static_cast<size_t>(kMaxPaintableTypes))
            return Status::error("type painting supports databases of at most " + std::to_string(kMaxPaintableTypes) +
                                 " types; this one has " + std::to_string(db.type_names.size()));
    }
    return Status::ok();
}

int passesAt(const SynthesisParams& params, int level, int coarsest) {
    return params.correction_passes + (level == coarsest && params.correction_passes > 0 ? kCoarsestLevelExtraPasses : 0);
}

int historyPassesAt(const SynthesisParams& params, int level, int coarsest) {
    return passesAt(params, level, coarsest) + (params.relax_offsets ? 1 : 0) +
           (params.drainage == Drainage::Breach ? 1 : 0);
}

std::vector<int> extraMargins(const SynthesisParams& params, int coarsest) {
    std::vector<int> margins(coarsest + 1, 0);
    margins[coarsest] = kSubpassReach * 4 * (passesAt(params, coarsest, coarsest) - params.correction_passes);
    if (params.relax_offsets)
        for (int level = 0; level <= coarsest; ++level) margins[level] += relaxationIterations(level);
    if (params.drainage == Drainage::Breach)
        for (int level = 0; level <= coarsest; ++level) margins[level] += 2 * breachRadius(level) + 1;
    return margins;
}

namespace {

// Output levels above the coarsest synthesized level M: the window's 2^d x 2^d blocks of level M
// averaged (d = output_level - M), so every output level shows the same terrain. Sources are those
// of each block's first pixel, scaled to the output level.
Result<SynthesisOutput> blockAverageOfCoarsest(const ExemplarDatabase& db, const PixelWindow& window,
                                               const SynthesisParams& params, int output_level, int coarsest,
                                               bool want_sources, SynthesisSteps& steps,
                                               const std::function<bool()>& stop_requested, size_t* peak_state_pixels) {
    const int d = output_level - coarsest, block = 1 << d;
    const PixelWindow fine{window.x * block, window.y * block, window.width * block, window.height * block};
    auto synthesized = runSynthesis(db, fine, params, coarsest, want_sources, steps, stop_requested, peak_state_pixels);
    if (!synthesized) return synthesized.status();
    const SynthesisOutput& in = synthesized.value();
    SynthesisOutput out;
    out.heights = Heightfield(window.width, window.height, db.meters_per_pixel * std::ldexp(1.0, output_level));
    if (want_sources) {
        out.source_x.resize(out.heights.size());
        out.source_y.resize(out.heights.size());
        out.source_exemplar.resize(out.heights.size());
    }
    const float scale = 1.0f / static_cast<float>(block);
    for (int y = 0; y < window.height; ++y)
        for (int x = 0; x < window.width; ++x) {
            double sum = 0.0;
            for (int by = 0; by < block; ++by)
                for (int bx = 0; bx < block; ++bx) sum += in.heights.at(x * block + bx, y * block + by);
            const size_t o = static_cast<size_t>(y) * window.width + x;
            out.heights.heights[o] = static_cast<float>(sum / static_cast<double>(block * block));
            if (!want_sources) continue;
            const size_t first = static_cast<size_t>(y) * block * fine.width + static_cast<size_t>(x) * block;
            out.source_x[o] = in.source_x[first] * scale;
            out.source_y[o] = in.source_y[first] * scale;
            out.source_exemplar[o] = in.source_exemplar[first];
        }
    out.history = in.history;
    return out;
}

}  // namespace

Result<SynthesisOutput> runSynthesis(const ExemplarDatabase& db, const PixelWindow& window,
                                     const SynthesisParams& params, int output_level, bool want_sources,
                                     SynthesisSteps& steps, const std::function<bool()>& stop_requested,
                                     size_t* peak_state_pixels) {
    Status valid = validateRequest(db, window, params, output_level);
    if (!valid) return valid;
    const int coarsest = coarsestLevel(db, params);
    if (output_level > coarsest)
        return blockAverageOfCoarsest(db, window, params, output_level, coarsest, want_sources, steps, stop_requested,
                                      peak_state_pixels);
    const bool drain = params.drainage == Drainage::Breach;
    const SynthesisPlan plan =
        planSynthesis(window, output_level, coarsest, params.correction_passes, extraMargins(params, coarsest));
    size_t peak = 0;
    auto history = params.record_history ? std::make_shared<SynthesisHistory>() : nullptr;
    if (history) history->levels.resize(coarsest + 1);
    auto correctLevel = [&](int level) -> Status {
        const LevelRegion& region = plan.regions[level];
        const std::vector<uint8_t> coherence =
            params.previous ? coherenceCodes(params.coherence.get(), level, region) : std::vector<uint8_t>();
        const int passes = passesAt(params, level, coarsest);
        if (history) {
            history->levels[level] = {region.x, region.y, region.width, region.height, {}};
            history->levels[level].passes.resize(historyPassesAt(params, level, coarsest));
        }
        if (level < output_level + params.preview_levels && level < coarsest) {
            // A preview level: the upsampled state, with what is not Free kept from the last pass.
            Status s = steps.previewLevel(level, region, coherence,
                                          previousPass(params.previous.get(), level,
                                                       historyPassesAt(params, level, coarsest) - 1, region));
            if (!s || !history) return s;
            auto& recorded = history->levels[level].passes;
            s = steps.recordPass(level, region, recorded[0]);
            for (size_t pass = 1; pass < recorded.size(); ++pass) recorded[pass] = recorded[0];
            return s;
        }
        const constraints::LevelConstraints level_constraints =
            constraints::constraintsForLevel(params.constraints.get(), level, params.first_constrained_level,
                                             params.hold_on_free_levels, region, db.meters_per_pixel);
        Status begun = steps.beginLevel(level, region, level_constraints, coherence, params.seed);
        if (!begun) return begun;
        int subpass = 0;
        for (int pass = 0; pass < passes; ++pass) {
            Status s = steps.beginPass(level, region, previousPass(params.previous.get(), level, pass, region));
            if (!s) return s;
            for (const auto& parity : kSubpassParity) {
                const int inset = kSubpassReach * ++subpass;
                s = steps.correct(level, region, parity[0], parity[1], inset);
                if (!s) return s;
            }
            if (history) {
                s = steps.recordPass(level, region, history->levels[level].passes[pass]);
                if (!s) return s;
            }
        }
        int recorded = passes;  // the history's next pass
        if (params.relax_offsets) {
            // Offset relaxation (offset_relaxation.h); frozen pixels take the previous synthesis's
            // relaxed state.
            const PassHistory relaxed = previousPass(params.previous.get(), level, recorded, region);
            Status s = steps.relax(level, region, relaxationIterations(level),
                                   {&coherence, &relaxed, &level_constraints.blend});
            if (s && history) s = steps.recordPass(level, region, history->levels[level].passes[recorded]);
            if (!s) return s;
            ++recorded;
        }
        if (!drain) return Status::ok();
        // Drainage (drainage_breach.h): breach the level's pits; frozen pixels take the previous
        // synthesis's drained state.
        const PassHistory drained = previousPass(params.previous.get(), level, recorded, region);
        Status s = steps.drain(level, region, breachRadius(level),
                               {&coherence, &drained, &level_constraints.blend, steps.depthMargin(level),
                                level >= kBreachToEdgeFromLevel, plan.needed[level], &steps.basinExemplars(),
                                &steps.levelGround(level), LevelGround::tolerance(db)});
        if (!s) return s;
        return history ? steps.recordPass(level, region, history->levels[level].passes.back()) : Status::ok();
    };
    // Between levels: the one place a synthesis can stop without leaving half a level behind.
    const auto stopped = [&] { return stop_requested && stop_requested(); };
    if (stopped()) return Status::error(kSynthesisStopped);
    Status s = steps.init(coarsest, plan.regions[coarsest], params.seed);
    if (!s) return s;
    for (int level = coarsest; level >= output_level; --level) {
        if (level < coarsest && stopped()) return Status::error(kSynthesisStopped);
        if (level < coarsest) {
            // A preview level is not jittered: no correction follows to make the jitter coherent;
            // nor are the finest levels (kUnjitteredLevels).
            const bool preview = level < output_level + params.preview_levels;
            const float jitter = preview || level < kUnjitteredLevels ? 0.0f : params.jitter;
            s = steps.upsample(level, plan.regions[level + 1], plan.regions[level], jitter,
                               params.seed, params.constraints ? &params.constraints->types : nullptr);
            if (!s) return s;
            peak = std::max(peak, plan.regions[level].pixels() + plan.regions[level + 1].pixels());
        }
        s = correctLevel(level);
        if (!s) return s;
    }
    SynthesisOutput output;
    const double spacing = db.meters_per_pixel * std::ldexp(1.0, output_level);
    output.heights = Heightfield(window.width, window.height, spacing);
    if (want_sources) {
        output.source_x.resize(output.heights.size());
        output.source_y.resize(output.heights.size());
        output.source_exemplar.resize(output.heights.size());
    }
    s = steps.resolve(output_level, plan.regions[output_level], plan.output, output, want_sources);
    if (!s) return s;
    output.history = std::move(history);
    if (peak_state_pixels) *peak_state_pixels = std::max(peak, plan.regions[coarsest].pixels());
    return output;
}

}  // namespace terrasynth::synth

namespace terrasynth {

int coarsestSynthesizedLevel(const ExemplarDatabase& db, const SynthesisParams& params) {
    return synth::coarsestLevel(db, params);
}

}  // namespace terrasynth
