// `terrasynth stats a.png [--vs b.png] [--sources src.png] [--json]`: geomorphological realism
// statistics of a terrain and, with --vs, per-metric distances to a second terrain read against the
// spread between a's own quadrants; with --sources, which parts of its exemplars a synthesis drew
// from (docs/realism.md explains every figure).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "command_registry.h"
#include "source_usage_report.h"
#include "terrasynth/heightfield_io.h"
#include "terrasynth/terrain_stats.h"

namespace terrasynth::cli {
namespace {

struct StatsOptions {
    std::string a, b, sources;
    bool json = false;
};

const char* kCommand = "stats";

// ---- text output

void printDistribution(const char* label, const Distribution& d, double scale, const char* unit) {
    std::printf("  %-22s mean %10.4g  median %10.4g  p10 %10.4g  p90 %10.4g  (%s)\n", label, d.mean * scale,
                d.median * scale, d.p10 * scale, d.p90 * scale, unit);
}

void printSummary(const std::string& path, const TerrainStats& s) {
    std::printf("%s: %dx%d samples at %.4g x %.4g m/pixel\n", path.c_str(), s.width, s.height, s.meters_per_pixel_x,
                s.meters_per_pixel_y);
    printDistribution("slope", s.slope_deg, 1.0, "deg");
    printDistribution("profile curvature", s.profile_curvature, 1000.0, "1/km, + convex");
    printDistribution("plan curvature", s.plan_curvature, 1000.0, "1/km, + convex");
    std::printf("  %-22s profile p90-p10 %.4g, plan p90-p10 %.4g (1/km)\n", "curvature spread",
                1000.0 * (s.profile_curvature.p90 - s.profile_curvature.p10),
                1000.0 * (s.plan_curvature.p90 - s.plan_curvature.p10));
    printDistribution("local relief 9x9", s.local_relief_m, 1.0, "m");
    const Distribution& a = s.drainage_area_m2;
    std::printf("  %-22s median %.4g  p90 %.4g  p99 %.4g  max %.4g (m^2); exceedance exponent tau %.3f\n",
                "drainage area", a.median, a.p90, a.p99, a.max, s.drainage_exceedance_exponent);
    std::printf("  %-22s pit share %.4f%%  depression share %.3f%%\n", "pits", 100.0 * s.pit_share,
                100.0 * s.depression_share);
    std::printf("  %-22s", "landforms");
    for (int c = 0; c < kLandformCount; ++c)
        std::printf(" %s %.1f%%", landformName(static_cast<Landform>(c)), 100.0 * s.landform_share[c]);
    std::printf("\n  %-22s 1D-equivalent %.3f (2D %.3f, Hurst %.3f, r^2 %.3f, tile %d)\n", "spectral slope",
                s.spectrum.slope_1d, s.spectrum.slope_2d, s.spectrum.hurst, s.spectrum.fit_r2, s.spectrum.tile_size);
}

void printDistances(const StatsDistance& d, const ReferenceSpread* spread) {
    std::printf("distances (W1 in the metric's units; KS 0..1)%s\n",
                spread ? "; reference = spread between the first terrain's quadrants" : "");
    std::printf("  %-18s %12s %8s %8s", "metric", "W1/|diff|", "unit", "KS");
    if (spread) std::printf(" %12s %12s %8s", "ref median", "ref max", "d/max");
    std::printf("\n");
    const SpreadVerdict verdict = spread ? judgeAgainstSpread(d, *spread) : SpreadVerdict();
    for (int m = 0; m < kMetricCount; ++m) {
        const Metric metric = static_cast<Metric>(m);
        std::printf("  %-18s %12.4g %8s %8.4f", metricName(metric), d.metric[m].value, metricUnit(metric),
                    d.metric[m].ks);
        if (spread)
            std::printf(" %12.4g %12.4g %8.2f%s", spread->median.metric[m].value, spread->max.metric[m].value,
                        verdict.ratio[m], verdict.ratio[m] <= 1.0 ? "" : "  outside");
        std::printf("\n");
    }
}

// ---- JSON output

nlohmann::json toJson(const Distribution& d) {
    return {{"mean", d.mean}, {"stddev", d.stddev}, {"min", d.min}, {"p10", d.p10}, {"median", d.median},
            {"p90", d.p90}, {"p99", d.p99}, {"max", d.max}, {"samples", d.samples}};
}

// NaN is not JSON; undefined figures become null.
nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::json toJson(const std::string& path, const TerrainStats& s) {
    nlohmann::json landforms;
    for (int c = 0; c < kLandformCount; ++c) landforms[landformName(static_cast<Landform>(c))] = s.landform_share[c];
    return {{"file", path},
            {"width", s.width},
            {"height", s.height},
            {"meters_per_pixel", {s.meters_per_pixel_x, s.meters_per_pixel_y}},
            {"slope_deg", toJson(s.slope_deg)},
            {"profile_curvature_per_m", toJson(s.profile_curvature)},
            {"plan_curvature_per_m", toJson(s.plan_curvature)},
            {"local_relief_m", toJson(s.local_relief_m)},
            {"drainage_area_m2", toJson(s.drainage_area_m2)},
            {"drainage_exceedance_exponent", number(s.drainage_exceedance_exponent)},
            {"pit_share", s.pit_share},
            {"depression_share", s.depression_share},
            {"landform_share", landforms},
            {"spectrum",
             {{"slope_1d", number(s.spectrum.slope_1d)},
              {"slope_2d", number(s.spectrum.slope_2d)},
              {"hurst", number(s.spectrum.hurst)},
              {"fit_r2", s.spectrum.fit_r2},
              {"tile_size", s.spectrum.tile_size}}}};
}

nlohmann::json toJson(const StatsDistance& d) {
    nlohmann::json out;
    for (int m = 0; m < kMetricCount; ++m) {
        const Metric metric = static_cast<Metric>(m);
        out[metricName(metric)] = {
            {"value", number(d.metric[m].value)}, {"ks", number(d.metric[m].ks)}, {"unit", metricUnit(metric)}};
    }
    return out;
}

// ---- the command

Result<Heightfield> load(const std::string& path) {
    auto exemplar = readExemplar(path);
    if (!exemplar) return exemplar.status();
    return std::move(exemplar->field);
}

std::string spacingText(double x, double y) {
    char text[64];
    if (std::fabs(x / y - 1.0) < 1e-3) std::snprintf(text, sizeof text, "%.6g m/pixel", x);
    else std::snprintf(text, sizeof text, "%.6g x %.6g m/pixel", x, y);
    return text;
}

bool isotropic(const Heightfield& f) { return std::fabs(f.meters_per_pixel_x / f.meters_per_pixel_y - 1.0) < 1e-3; }

void run(const StatsOptions& o) {
    if (o.a.empty() && o.sources.empty()) return fail(kCommand, "give a terrain, --sources src.png, or both");
    nlohmann::json sources;
    if (!o.sources.empty()) {
        auto measured = measureSourcesMap(o.sources);
        if (!measured) return fail(kCommand, measured.message());
        sources = std::move(measured.value());
    }
    if (o.a.empty()) {
        if (o.json) std::printf("%s\n", jsonText(nlohmann::json{{"sources", sources}}, 2).c_str());
        else printSourcesReport(sources);
        return;
    }
    if (!sources.is_null() && !o.json) printSourcesReport(sources);
    auto a = load(o.a);
    if (!a) return fail(kCommand, a.message());
    Heightfield field_a = std::move(a.value());
    std::string note;
    nlohmann::json report;
    // Distributions only compare at equal spacing; an anisotropic a is first made square so b can match it.
    if (!o.b.empty() && !isotropic(field_a)) {
        const double spacing = std::max(field_a.meters_per_pixel_x, field_a.meters_per_pixel_y);
        note += "resampled " + o.a + " from " + spacingText(field_a.meters_per_pixel_x, field_a.meters_per_pixel_y) +
                " to " + spacingText(spacing, spacing) + "\n";
        field_a = resampleToSpacing(field_a, spacing);
    }
    auto stats_a = computeTerrainStats(field_a);
    if (!stats_a) return fail(kCommand, o.a + ": " + stats_a.message());

    if (o.b.empty()) {
        if (o.json && !sources.is_null())
            std::printf("%s\n", jsonText(nlohmann::json{{"a", toJson(o.a, *stats_a)}, {"sources", sources}}, 2).c_str());
        else if (o.json) std::printf("%s\n", jsonText(toJson(o.a, *stats_a), 2).c_str());
        else printSummary(o.a, *stats_a);
        return;
    }

    auto b = load(o.b);
    if (!b) return fail(kCommand, b.message());
    Heightfield field_b = std::move(b.value());
    const double spacing = field_a.meters_per_pixel_x;
    if (std::fabs(field_b.meters_per_pixel_x / spacing - 1.0) > 1e-3 ||
        std::fabs(field_b.meters_per_pixel_y / spacing - 1.0) > 1e-3) {
        note += "resampled " + o.b + " from " + spacingText(field_b.meters_per_pixel_x, field_b.meters_per_pixel_y) +
                " to " + spacingText(spacing, spacing) + " (the first terrain's spacing)\n";
        field_b = resampleToSpacing(field_b, spacing);
    }
    auto stats_b = computeTerrainStats(field_b);
    if (!stats_b) return fail(kCommand, o.b + ": " + stats_b.message());
    const StatsDistance distance = compareStats(*stats_a, *stats_b);

    // The yardstick: how far apart a's own quadrants are.
    std::unique_ptr<ReferenceSpread> spread;
    const int quadrant = std::min(field_a.width, field_a.height) / 2;
    if (quadrant >= 32) {
        auto r = referenceSpread({field_a}, quadrant, spacing);
        if (r) spread = std::make_unique<ReferenceSpread>(std::move(r.value()));
    }

    if (o.json) {
        report["a"] = toJson(o.a, *stats_a);
        report["b"] = toJson(o.b, *stats_b);
        report["distance"] = toJson(distance);
        if (!sources.is_null()) report["sources"] = sources;
        if (!note.empty()) report["note"] = note;
        if (spread)
            report["reference_spread"] = {{"source", "quadrants of a"},   {"piece_size", spread->piece_size},
                                          {"pairs", spread->pairs},       {"median", toJson(spread->median)},
                                          {"max", toJson(spread->max)}};
        std::printf("%s\n", jsonText(report, 2).c_str());
        return;
    }
    if (!note.empty()) std::printf("%s", note.c_str());
    printSummary(o.a, *stats_a);
    printSummary(o.b, *stats_b);
    printDistances(distance, spread.get());
}

void addStatsCommand(CLI::App& app) {
    auto options = std::make_shared<StatsOptions>();
    CLI::App* cmd = app.add_subcommand(
        "stats", "Realism statistics of a terrain (slope, curvature, relief, drainage, pits, landforms, spectrum)");
    cmd->add_option("terrain", options->a, "Heightfield in any exemplar format (PNG + sidecar, .f32 + sidecar, ...)");
    cmd->add_option("--vs", options->b,
                    "Second terrain: print per-metric distances (it is resampled to the first one's spacing)");
    cmd->add_option("--sources", options->sources,
                    "Sources map of a synthesis (synth --sources): share of the output per exemplar and from its "
                    "flattest 30% by 9x9 local relief");
    cmd->add_flag("--json", options->json, "Print JSON instead of text");
    setAction(cmd, [options] { run(*options); });
}

const CommandRegistration kReg{"stats", 40, addStatsCommand};

}  // namespace
}  // namespace terrasynth::cli
