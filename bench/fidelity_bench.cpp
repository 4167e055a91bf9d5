// Constraint fidelity figures (issue 18) at full size: random curve constraints, held (lifted) and
// plain, on random seeds. Not a Google Benchmark: a bench CLI that prints the figures.
// Run: build/bin/fidelity_bench [--db default|shared] [--size 1024] [--cases 30] [--first 0]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>

#include "terrasynth/curve_course.h"
#include "terrasynth/heightfield_io.h"
#include "terrasynth/incremental.h"
#include "terrasynth/terrain_stats.h"
#include "terrasynth/synthesizer.h"

using namespace terrasynth;

namespace {

struct Args {
    std::string db = "shared";
    int size = 1024;
    int cases = 30;
    int first = 0;
    double spacing = 16.0;
    int rounds = 8;
    std::string what = "curves";
};

double quantile(std::vector<float> v, double q) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    return v[std::min(v.size() - 1, static_cast<size_t>(q * static_cast<double>(v.size())))];
}

std::vector<float> absolute(std::vector<float> v) {
    for (float& x : v) x = std::fabs(x);
    return v;
}

double now() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// A random curve set: 1-2 curves of 3-8 course points (random walk), 2-5 widgets with heights around
// the free terrain's, random gradients and reaches; splines or polylines, some closed.
std::vector<CurveConstraint> randomCurves(std::mt19937& rng, const Heightfield& free, int size) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const int count = unit(rng) < 0.4 ? 2 : 1;
    std::vector<CurveConstraint> curves;
    for (int c = 0; c < count; ++c) {
        CurveConstraint curve;
        const int points = 3 + static_cast<int>(unit(rng) * 6);
        const double lo = 0.12 * size, hi = 0.88 * size;
        double x = lo + unit(rng) * (hi - lo), y = lo + unit(rng) * (hi - lo);
        double angle = unit(rng) * 6.283185307;
        for (int k = 0; k < points; ++k) {
            curve.course.emplace_back(x, y);
            // Turns of at most 75 degrees: a course does not double back onto itself (its two
            // branches would ask for two heights a few pixels apart).
            angle += (unit(rng) - 0.5) * 2.6;
            const double step = (0.05 + 0.15 * unit(rng)) * size;
            x = std::clamp(x + step * std::cos(angle), lo, hi);
            y = std::clamp(y + step * std::sin(angle), lo, hi);
        }
        if (unit(rng) < 0.25) curve.course.push_back(curve.course.front());
        curve.spline = unit(rng) < 0.5;
        double mean = 0.0;
        for (auto [px, py] : curve.course) mean += free.at(static_cast<int>(px), static_cast<int>(py));
        mean /= static_cast<double>(curve.course.size());
        const double base = mean - 600.0 + 1500.0 * unit(rng);
        const int widgets = 2 + static_cast<int>(unit(rng) * 4);
        for (int k = 0; k < widgets; ++k) {
            CurveWidget w;
            w.t = widgets == 1 ? 0.0 : (k + 0.8 * (unit(rng) - 0.5)) / (widgets - 1);
            w.t = std::clamp(w.t, 0.0, 1.0);
            w.height_m = static_cast<float>(base + 400.0 * (unit(rng) - 0.5));
            w.left_gradient = static_cast<float>(-0.4 + 0.8 * unit(rng));
            w.right_gradient = static_cast<float>(-0.4 + 0.8 * unit(rng));
            w.left_reach_px = static_cast<float>(16.0 + 104.0 * unit(rng));
            w.right_reach_px = static_cast<float>(16.0 + 104.0 * unit(rng));
            curve.widgets.push_back(w);
        }
        std::sort(curve.widgets.begin(), curve.widgets.end(), [](const CurveWidget& a, const CurveWidget& b) { return a.t < b.t; });
        curves.push_back(curve);
    }
    return curves;
}

// Detail on the course itself: median |Laplacian| (m) at the course's pixels over the same at
// pixels 6 px to either side. A course held smooth on the free levels would show below 1.
double courseDetailRatio(const Heightfield& h, const std::vector<CurveConstraint>& curves) {
    auto laplacian = [&](double x, double y) {
        const int ix = static_cast<int>(std::lround(x)), iy = static_cast<int>(std::lround(y));
        if (ix < 1 || iy < 1 || ix + 1 >= h.width || iy + 1 >= h.height) return -1.0f;
        return std::fabs(h.at(ix - 1, iy) + h.at(ix + 1, iy) + h.at(ix, iy - 1) + h.at(ix, iy + 1) - 4 * h.at(ix, iy));
    };
    std::vector<float> on, beside;
    for (size_t i = 0; i < curves.size(); ++i)
        for (const CurveCourseSample& c : sampleCurveCourse(curves, i, 1.0)) {
            const float a = laplacian(c.x, c.y), b = laplacian(c.x + 6 * c.left_x, c.y + 6 * c.left_y),
                        d = laplacian(c.x - 6 * c.left_x, c.y - 6 * c.left_y);
            if (a >= 0) on.push_back(a);
            if (b >= 0) beside.push_back(b);
            if (d >= 0) beside.push_back(d);
        }
    return quantile(on, 0.5) / std::max(1e-6, quantile(beside, 0.5));
}

// Median slope (degrees) and median |profile curvature| (1/km) inside the curves' reach and outside.
struct BandStats {
    double slope_in = 0, slope_out = 0, curvature_in = 0, curvature_out = 0;
};
BandStats bandStats(const Heightfield& h, const std::vector<CurveConstraint>& curves) {
    std::vector<uint8_t> inside(h.heights.size(), 0);
    for (size_t i = 0; i < curves.size(); ++i)
        for (const CurveCourseSample& c : sampleCurveCourse(curves, i, 2.0)) {
            const int r = static_cast<int>(std::max(c.left_reach_px, c.right_reach_px));
            for (int dy = -r; dy <= r; ++dy)
                for (int dx = -r; dx <= r; ++dx) {
                    const int x = static_cast<int>(c.x) + dx, y = static_cast<int>(c.y) + dy;
                    if (x < 0 || y < 0 || x >= h.width || y >= h.height || dx * dx + dy * dy > r * r) continue;
                    const double side = dx * c.left_x + dy * c.left_y;  // >= 0: left
                    if (std::hypot(dx, dy) <= (side >= 0 ? c.left_reach_px : c.right_reach_px)) inside[static_cast<size_t>(y) * h.width + x] = 1;
                }
        }
    const std::vector<float> slope = slopeDegrees(h);
    const CurvatureMaps k = curvatures(h);
    std::vector<float> si, so, ki, ko;
    for (int y = 2; y < h.height - 2; ++y)
        for (int x = 2; x < h.width - 2; ++x) {
            const size_t i = static_cast<size_t>(y) * h.width + x;
            (inside[i] ? si : so).push_back(slope[i]);
            if (std::isfinite(k.profile[i])) (inside[i] ? ki : ko).push_back(1000.0f * std::fabs(k.profile[i]));
        }
    return {quantile(si, 0.5), quantile(so, 0.5), quantile(ki, 0.5), quantile(ko, 0.5)};
}

struct Figures {
    double median = 0.0, p95 = 0.0, gradient = 0.0;  // relative to the relief; gradient in m/m
};

Figures measure(const Heightfield& h, const std::vector<CurveConstraint>& curves, double mpp) {
    std::vector<float> errors, gradients;
    for (size_t i = 0; i < curves.size(); ++i) {
        const CurveHold hold = measureCurveHold(h, 0, 0, curves, i, mpp);
        errors.insert(errors.end(), hold.height_error_m.begin(), hold.height_error_m.end());
        gradients.insert(gradients.end(), hold.gradient_error.begin(), hold.gradient_error.end());
    }
    const HeightRange r = heightRange(h);
    const double relief = r.max - r.min;
    return {quantile(absolute(errors), 0.5) / relief, quantile(absolute(errors), 0.95) / relief,
            quantile(absolute(gradients), 0.5)};
}

int runCurves(const Args& args, Synthesizer& s) {
    const double mpp = s.database().meters_per_pixel;
    const PixelWindow extent{0, 0, args.size, args.size};
    std::vector<float> plain_median, plain_p95, held_median, held_p95, plain_gradient, held_gradient, seconds;
    for (int k = args.first; k < args.first + args.cases; ++k) {
        std::mt19937 rng(1000 + k);
        SynthesisParams params;
        params.seed = 1 + static_cast<uint32_t>(rng() % 100000);
        auto free = s.synthesize(extent, params);
        if (!free) return std::fprintf(stderr, "%s\n", free.message().c_str()), 1;
        auto c = std::make_shared<SynthesisConstraints>();
        c->curves = randomCurves(rng, free->heights, args.size);
        if (std::getenv("TS_STRAIGHT")) {
            CurveConstraint straight;
            straight.course = {{100.0, 256.0}, {400.0, 256.0}};
            straight.spline = false;
            CurveWidget w;
            w.height_m = free->heights.at(250, 256);
            w.left_gradient = 0.2f, w.right_gradient = -0.3f, w.left_reach_px = 60, w.right_reach_px = 60;
            straight.widgets = {w};
            c->curves = {straight};
        }
        params.constraints = c;
        auto plain = s.synthesize(extent, params);
        if (!plain) return std::fprintf(stderr, "%s\n", plain.message().c_str()), 1;
        params.hold_on_free_levels = true;
        auto banded = s.synthesize(extent, params);
        if (!banded) return std::fprintf(stderr, "%s\n", banded.message().c_str()), 1;
        const double start = now();
        CurveLiftOptions options;
        options.station_spacing_px = args.spacing;
        options.max_rounds = args.rounds;
        SynthesisParams lift_params = params;
        if (std::getenv("TS_LIFT_PLAIN")) lift_params.hold_on_free_levels = false;
        auto lifted = liftCurveConstraints(s, lift_params, options);
        if (!lifted) return std::fprintf(stderr, "%s\n", lifted.message().c_str()), 1;
        const double lift_s = now() - start;
        params.constraints = lifted.value();
        auto held = s.synthesize(extent, params);
        if (!held) return std::fprintf(stderr, "%s\n", held.message().c_str()), 1;
        const Figures a = measure(plain->heights, c->curves, mpp), b = measure(held->heights, c->curves, mpp);
        const Figures m = measure(banded->heights, c->curves, mpp);
        if (std::getenv("TS_STRAIGHT")) {
            for (int d : {0, 8, 15, 30, 45, 59, 70})
                std::printf("d %d: north %.1f south %.1f (course %.1f) plain north %.1f south %.1f\n", d, held->heights.at(250, 256 - d),
                            held->heights.at(250, 256 + d), held->heights.at(250, 256), plain->heights.at(250, 256 - d),
                            plain->heights.at(250, 256 + d));
        }
        std::printf("case %3d own pixels held, no lift: median %.2f%% p95 %.2f%%\n", k, 100 * m.median, 100 * m.p95);
        {
            const BandStats bp = bandStats(plain->heights, c->curves), bh = bandStats(held->heights, c->curves);
            std::printf("case %3d course detail ratio plain %.2f held %.2f | slope in/out plain %.1f/%.1f held %.1f/%.1f | "
                        "|profile curvature| 1/km in/out plain %.3f/%.3f held %.3f/%.3f\n",
                        k, courseDetailRatio(plain->heights, c->curves), courseDetailRatio(held->heights, c->curves), bp.slope_in,
                        bp.slope_out, bh.slope_in, bh.slope_out, bp.curvature_in, bp.curvature_out, bh.curvature_in, bh.curvature_out);
        }
        if (const char* png = std::getenv("TS_PNG")) {
            writeHillshadePng(std::string(png) + "_plain_" + std::to_string(k) + ".png", plain->heights);
            writeHillshadePng(std::string(png) + "_held_" + std::to_string(k) + ".png", held->heights);
        }
        if (std::getenv("TS_PROFILE")) {
            for (size_t i = 0; i < c->curves.size(); ++i) {
                const auto samples = sampleCurveCourse(lifted.value()->curves, i, 1.0);
                const CurveHold hp = measureCurveHold(plain->heights, 0, 0, c->curves, i, mpp);
                const CurveHold hh = measureCurveHold(held->heights, 0, 0, c->curves, i, mpp);
                for (size_t j = 0; j < samples.size() && j < hh.height_error_m.size(); j += 4)
                    std::printf("  curve %zu s %6.1f x %6.1f y %6.1f target %7.1f lift %7.1f plain %7.1f held %7.1f  L %.2f/%.0f R %.2f/%.0f\n", i,
                                samples[j].s, samples[j].x, samples[j].y, samples[j].height_m, samples[j].lift_m,
                                hp.height_error_m[j], hh.height_error_m[j], samples[j].left_gradient, samples[j].left_reach_px,
                                samples[j].right_gradient, samples[j].right_reach_px);
            }
        }
        std::printf("case %3d seed %6u curves %zu%s: plain median %.2f%% p95 %.2f%% grad %.3f | held median %.2f%% p95 "
                    "%.2f%% grad %.3f | lift %.2f s\n",
                    k, params.seed, c->curves.size(), c->curves[0].spline ? " spline" : " polyline", 100 * a.median,
                    100 * a.p95, a.gradient, 100 * b.median, 100 * b.p95, b.gradient, lift_s);
        std::fflush(stdout);
        plain_median.push_back(a.median), plain_p95.push_back(a.p95), plain_gradient.push_back(a.gradient);
        held_median.push_back(b.median), held_p95.push_back(b.p95), held_gradient.push_back(b.gradient);
        seconds.push_back(static_cast<float>(lift_s));
    }
    std::printf("\n%d cases, %dx%d, %s database:\n", args.cases, args.size, args.size, args.db.c_str());
    std::printf("plain: median of medians %.2f%%, worst median %.2f%%, median p95 %.2f%%, worst p95 %.2f%%, gradient %.3f\n",
                100 * quantile(plain_median, 0.5), 100 * quantile(plain_median, 1.0), 100 * quantile(plain_p95, 0.5),
                100 * quantile(plain_p95, 1.0), quantile(plain_gradient, 0.5));
    std::printf("held:  median of medians %.2f%%, worst median %.2f%%, median p95 %.2f%%, worst p95 %.2f%%, gradient %.3f\n",
                100 * quantile(held_median, 0.5), 100 * quantile(held_median, 1.0), 100 * quantile(held_p95, 0.5),
                100 * quantile(held_p95, 1.0), quantile(held_gradient, 0.5));
    std::printf("lift time: median %.2f s, max %.2f s\n", quantile(seconds, 0.5), quantile(seconds, 1.0));
    return 0;
}

// How far the finished level-0 heights lie from the level-L ones (bilinear) along random lines:
// the detail the free finest levels add, which no lift on the constrained levels can take out.
int runDetail(const Args& args, Synthesizer& s) {
    const PixelWindow extent{0, 0, args.size, args.size};
    for (int k = args.first; k < args.first + args.cases; ++k) {
        SynthesisParams params;
        params.seed = 1 + k * 7919;
        auto h0 = s.synthesize(extent, params, 0);
        if (!h0) return 1;
        const HeightRange r = heightRange(h0->heights);
        std::printf("seed %u relief %.0f m:", params.seed, r.max - r.min);
        for (int level = 1; level <= 3; ++level) {
            const int cell = 1 << level;
            auto hl = s.synthesize({0, 0, args.size / cell, args.size / cell}, params, level);
            if (!hl) return 1;
            std::vector<float> diff;
            for (int y = 8; y < args.size - 8; y += 3)
                for (int x = 8; x < args.size - 8; x += 3) {
                    const double lx = (x + 0.5) / cell - 0.5, ly = (y + 0.5) / cell - 0.5;
                    const int ix = static_cast<int>(std::floor(lx)), iy = static_cast<int>(std::floor(ly));
                    const double tx = lx - ix, ty = ly - iy;
                    const Heightfield& h = hl->heights;
                    const double top = h.at(ix, iy) + (h.at(ix + 1, iy) - h.at(ix, iy)) * tx;
                    const double bot = h.at(ix, iy + 1) + (h.at(ix + 1, iy + 1) - h.at(ix, iy + 1)) * tx;
                    diff.push_back(static_cast<float>(h0->heights.at(x, y) - (top + (bot - top) * ty)));
                }
            double mean = 0.0;
            for (float d : diff) mean += d;
            mean /= static_cast<double>(diff.size());
            for (float& d : diff) d -= static_cast<float>(mean);
            std::printf("  level %d: bias %.1f m, median |detail| %.1f m (%.2f%%), p95 %.1f m (%.2f%%)", level, mean,
                        quantile(absolute(diff), 0.5), 100 * quantile(absolute(diff), 0.5) / (r.max - r.min),
                        quantile(absolute(diff), 0.95), 100 * quantile(absolute(diff), 0.95) / (r.max - r.min));
        }
        std::printf("\n");
    }
    return 0;
}

// Direction (clockwise from north) in which the plane fitted over +-half pixels around (x, y) rises.
double planeDirectionDeg(const Heightfield& h, int x, int y, int half) {
    double east = 0.0, south = 0.0;
    for (int dy = -half; dy <= half; ++dy)
        for (int dx = -half; dx <= half; ++dx) {
            east += dx * h.at(x + dx, y + dy);
            south += dy * h.at(x + dx, y + dy);
        }
    return std::atan2(east, -south) * 180.0 / 3.14159265358979;
}

double angleBetweenDeg(double a, double b) { return std::fabs(std::remainder(a - b, 360.0)); }

// Random single points asked at 10-30 degrees of slope: direction error over the site's 7x7 pixels
// and over half the radius, plain, lifted (heights only) and held (own pixels + lifts).
int runPoints(const Args& args, Synthesizer& s) {
    const PixelWindow extent{0, 0, args.size, args.size};
    std::vector<float> errors[3][2], heights[3];
    for (int k = args.first; k < args.first + args.cases; ++k) {
        std::mt19937 rng(5000 + k);
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        SynthesisParams params;
        params.seed = 1 + static_cast<uint32_t>(rng() % 100000);
        auto free = s.synthesize(extent, params);
        if (!free) return 1;
        const HeightRange relief = heightRange(free->heights);
        auto c = std::make_shared<SynthesisConstraints>();
        PointConstraint p;
        p.x = std::floor(0.2 * args.size + unit(rng) * 0.6 * args.size);
        p.y = std::floor(0.2 * args.size + unit(rng) * 0.6 * args.size);
        p.height_m = free->heights.at(static_cast<int>(p.x), static_cast<int>(p.y)) + static_cast<float>(-500.0 + 1300.0 * unit(rng));
        p.slope_direction_deg = static_cast<float>(360.0 * unit(rng));
        p.slope_angle_deg = static_cast<float>(10.0 + 20.0 * unit(rng));
        p.radius_px = static_cast<float>(48.0 + 80.0 * unit(rng));
        c->points.push_back(p);
        std::printf("case %3d seed %6u slope %.0f deg towards %.0f, radius %.0f:", k, params.seed, p.slope_angle_deg,
                    p.slope_direction_deg, p.radius_px);
        for (int mode = 0; mode < 3; ++mode) {
            SynthesisParams q = params;
            q.constraints = c;
            q.hold_on_free_levels = mode == 2;
            if (mode > 0) {
                auto lifted = liftPointConstraints(s, q);
                if (!lifted) return 1;
                q.constraints = lifted.value();
            }
            auto out = s.synthesize(extent, q);
            if (!out) return 1;
            const int x = static_cast<int>(p.x), y = static_cast<int>(p.y);
            const double own = angleBetweenDeg(planeDirectionDeg(out->heights, x, y, 3), p.slope_direction_deg);
            const double wide = angleBetweenDeg(planeDirectionDeg(out->heights, x, y, static_cast<int>(p.radius_px / 2)), p.slope_direction_deg);
            const float error = std::fabs(out->heights.at(x, y) - p.height_m) / (relief.max - relief.min);
            if (std::getenv("TS_SITE")) {
                const double kDeg = 3.14159265358979 / 180.0, rise = std::tan(p.slope_angle_deg * kDeg) * s.database().meters_per_pixel;
                const double re = rise * std::sin(p.slope_direction_deg * kDeg), rs = -rise * std::cos(p.slope_direction_deg * kDeg);
                std::printf("\nmode %d (plane rises %.1f m/px east, %.1f south): height - site - plane\n", mode, re, rs);
                for (int dy = -3; dy <= 3; ++dy) {
                    for (int dx = -3; dx <= 3; ++dx)
                        std::printf(" %7.1f", out->heights.at(x + dx, y + dy) - p.height_m - (re * dx + rs * dy));
                    std::printf("\n");
                }
            }
            errors[mode][0].push_back(static_cast<float>(own));
            errors[mode][1].push_back(static_cast<float>(wide));
            heights[mode].push_back(error);
            std::printf(" | %s 7x7 %.1f r/2 %.1f h %.2f%%", mode == 0 ? "plain" : (mode == 1 ? "lifted" : "held"), own, wide, 100 * error);
        }
        std::printf("\n");
        std::fflush(stdout);
    }
    for (int mode = 0; mode < 3; ++mode)
        std::printf("%s: 7x7 direction error median %.1f max %.1f (beyond 15: %zu), r/2 median %.1f max %.1f, height median %.2f%% max %.2f%%\n",
                    mode == 0 ? "plain" : (mode == 1 ? "lifted" : "held"), quantile(errors[mode][0], 0.5), quantile(errors[mode][0], 1.0),
                    static_cast<size_t>(std::count_if(errors[mode][0].begin(), errors[mode][0].end(), [](float e) { return e > 15.0f; })),
                    quantile(errors[mode][1], 0.5), quantile(errors[mode][1], 1.0), 100 * quantile(heights[mode], 0.5),
                    100 * quantile(heights[mode], 1.0));
    return 0;
}

// One paste from every exemplar of the database: a random polygon inside the exemplar at level 0,
// pasted at the terrain's centre at the local height. Interior error against the exemplar's
// resampled heights + offset, and the step across the target's boundary against the local gradient.
int runPastes(const Args& args, Synthesizer& s) {
    const ExemplarDatabase& db = s.database();
    const PixelWindow extent{0, 0, args.size, args.size};
    SynthesisParams params;
    params.seed = 7;
    auto base = IncrementalTerrain::create(s, extent, params);
    if (!base) return std::fprintf(stderr, "%s\n", base.message().c_str()), 1;
    int failures = 0;
    for (size_t e = 0; e < db.exemplars.size(); ++e) {
        std::mt19937 rng(900 + static_cast<unsigned>(e));
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        const DatabaseLevel& l0 = db.levels[0];
        const AtlasRect& r = l0.rects[e];
        // A polygon of 7 vertices on a jittered ellipse, inside the exemplar's pixel centres.
        const double rx = std::min(0.45 * (r.width - 1), 0.35 * args.size), ry = std::min(0.45 * (r.height - 1), 0.35 * args.size);
        const double cx = 0.5 * (r.width - 1), cy = 0.5 * (r.height - 1);
        PasteConstraint paste;
        paste.exemplar = static_cast<int>(e);
        for (int k = 0; k < 7; ++k) {
            const double a = 6.283185307 * (k + 0.3 * unit(rng)) / 7.0, f = 0.7 + 0.3 * unit(rng);
            paste.source.emplace_back(cx + f * rx * std::cos(a), cy + f * ry * std::sin(a));
        }
        paste.dx = std::floor(0.5 * args.size - cx), paste.dy = std::floor(0.5 * args.size - cy);
        // The target polygon's pixels (centres inside; pasteTargetMask is the frozen part of them).
        std::vector<uint8_t> mask(static_cast<size_t>(args.size) * args.size, 0);
        for (int y = 0; y < args.size; ++y)
            for (int x = 0; x < args.size; ++x) {
                bool inside = false;
                const auto& poly = paste.source;
                for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
                    const double xi = poly[i].first + paste.dx, yi = poly[i].second + paste.dy;
                    const double xj = poly[j].first + paste.dx, yj = poly[j].second + paste.dy;
                    if ((yi > y) != (yj > y) && x < (xj - xi) * (y - yi) / (yj - yi) + xi) inside = !inside;
                }
                mask[static_cast<size_t>(y) * args.size + x] = inside;
            }
        double exemplar_mean = 0.0, terrain_mean = 0.0;
        size_t inside = 0;
        for (int y = 0; y < args.size; ++y)
            for (int x = 0; x < args.size; ++x) {
                if (!mask[static_cast<size_t>(y) * args.size + x]) continue;
                exemplar_mean += l0.height_m[static_cast<size_t>(r.y + y - paste.dy) * l0.width + r.x + x - paste.dx];
                terrain_mean += base->heights().at(x, y);
                ++inside;
            }
        paste.height_offset_m = static_cast<float>((terrain_mean - exemplar_mean) / static_cast<double>(inside));
        IncrementalTerrain terrain = std::move(base.value());
        const double start = now();
        Status st = terrain.paste(paste);
        const double paste_s = now() - start;
        if (!st) {
            std::printf("%-24s %4dx%-4d FAILED: %s\n", db.exemplars[e].name.c_str(), r.width, r.height, st.message().c_str());
            ++failures;
            base = IncrementalTerrain::create(s, extent, params);
            continue;
        }
        const Heightfield& h = terrain.heights();
        if (const char* png = std::getenv("TS_PNG")) writeHillshadePng(std::string(png) + "_paste_" + std::to_string(e) + ".png", h);
        // Distance to the boundary (Chebyshev, capped) to leave out the 8 px next to it.
        std::vector<float> interior, steps, gradient;
        auto in = [&](int x, int y) { return x >= 0 && y >= 0 && x < args.size && y < args.size && mask[static_cast<size_t>(y) * args.size + x]; };
        auto nearBoundary = [&](int x, int y, int d) {
            for (int dy = -d; dy <= d; ++dy)
                for (int dx = -d; dx <= d; ++dx)
                    if (in(x + dx, y + dy) != in(x, y)) return true;
            return false;
        };
        float worst = 0.0f;
        for (int y = 1; y + 1 < args.size; ++y)
            for (int x = 1; x + 1 < args.size; ++x) {
                const bool here = in(x, y);
                if (here) {
                    const float want = l0.height_m[static_cast<size_t>(r.y + y - paste.dy) * l0.width + r.x + x - paste.dx] + paste.height_offset_m;
                    const float err = std::fabs(h.at(x, y) - want);
                    worst = std::max(worst, err);
                    if (!nearBoundary(x, y, 8)) interior.push_back(err);
                }
                for (auto [dx, dy] : {std::pair<int, int>{1, 0}, {0, 1}}) {
                    const float step = std::fabs(h.at(x + dx, y + dy) - h.at(x, y));
                    if (in(x + dx, y + dy) != here) steps.push_back(step);
                    else if (nearBoundary(x, y, 8) && nearBoundary(x + dx, y + dy, 8)) gradient.push_back(step);
                }
            }
        if (std::getenv("TS_PROFILE")) {
            // Chamfer distance to the other side of the boundary (negative inside), then mean |dh| per bin.
            const int n = args.size;
            std::vector<float> dist(static_cast<size_t>(n) * n, 1e9f);
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x)
                    for (auto [dx, dy] : {std::pair<int, int>{1, 0}, {0, 1}, {-1, 0}, {0, -1}})
                        if (x + dx >= 0 && y + dy >= 0 && x + dx < n && y + dy < n && in(x + dx, y + dy) != in(x, y)) dist[static_cast<size_t>(y) * n + x] = 0.5f;
            for (int pass = 0; pass < 2; ++pass)
                for (int k = 0; k < n * n; ++k) {
                    const int i = pass == 0 ? k : n * n - 1 - k, x = i % n, y = i / n, sgn = pass == 0 ? -1 : 1;
                    float& d = dist[static_cast<size_t>(i)];
                    if (x + sgn >= 0 && x + sgn < n) d = std::min(d, dist[static_cast<size_t>(i + sgn)] + 1.0f);
                    if (y + sgn >= 0 && y + sgn < n) d = std::min(d, dist[static_cast<size_t>(i + sgn * n)] + 1.0f);
                }
            std::vector<double> sum(60, 0.0), count(60, 0.0);
            for (int y = 0; y + 1 < n; ++y)
                for (int x = 0; x + 1 < n; ++x) {
                    const float d = dist[static_cast<size_t>(y) * n + x] * (in(x, y) ? -1.0f : 1.0f);
                    const int bin = static_cast<int>(std::floor(d)) + 20;
                    if (bin < 0 || bin >= 60) continue;
                    sum[bin] += 0.5 * (std::fabs(h.at(x + 1, y) - h.at(x, y)) + std::fabs(h.at(x, y + 1) - h.at(x, y)));
                    count[bin] += 1.0;
                }
            std::printf("  |dh| by distance from the boundary (-20..+39):");
            for (int b = 0; b < 60; ++b) std::printf(" %.0f", count[b] > 0 ? sum[b] / count[b] : 0.0);
            std::printf("\n");
        }
        // Per boundary pair: the step over the mean |dh| of the non-crossing pairs within 4 px.
        std::vector<float> ratios;
        for (int y = 5; y + 5 < args.size; ++y)
            for (int x = 5; x + 5 < args.size; ++x)
                for (auto [dx, dy] : {std::pair<int, int>{1, 0}, {0, 1}}) {
                    if (in(x + dx, y + dy) == in(x, y)) continue;
                    double local = 0.0;
                    int count = 0;
                    for (int v = -4; v <= 4; ++v)
                        for (int u = -4; u <= 4; ++u)
                            for (auto [ex, ey] : {std::pair<int, int>{1, 0}, {0, 1}}) {
                                const int ax = x + u, ay = y + v;
                                if (in(ax + ex, ay + ey) != in(ax, ay)) continue;
                                local += std::fabs(h.at(ax + ex, ay + ey) - h.at(ax, ay)), ++count;
                            }
                    ratios.push_back(static_cast<float>(std::fabs(h.at(x + dx, y + dy) - h.at(x, y)) / std::max(1e-3, local / count)));
                }
        std::printf("  step / local gradient: median %.2f p90 %.2f\n", quantile(ratios, 0.5), quantile(ratios, 0.9));
        double step_mean = 0.0, gradient_mean = 0.0;
        for (float v : steps) step_mean += v / static_cast<double>(steps.size());
        for (float v : gradient) gradient_mean += v / static_cast<double>(gradient.size());
        std::printf("  step mean %.1f m over %zu pairs, local gradient mean %.1f m over %zu pairs\n", step_mean, steps.size(),
                    gradient_mean, gradient.size());
        const bool seamless = quantile(steps, 0.5) <= quantile(gradient, 0.5);
        std::printf("%-24s %4dx%-4d polygon %zu px: interior median error %.4f m (worst inside %.4f m), boundary step median %.1f m "
                    "p90 %.1f m, local gradient median %.1f m p90 %.1f m%s, %.0f ms\n",
                    db.exemplars[e].name.c_str(), r.width, r.height, inside, quantile(interior, 0.5), worst, quantile(steps, 0.5),
                    quantile(steps, 0.9), quantile(gradient, 0.5), quantile(gradient, 0.9), seamless ? "" : "  STEP", 1000 * paste_s);
        std::fflush(stdout);
        base = IncrementalTerrain::create(s, extent, params);
    }
    return failures ? 1 : 0;
}

// Synthesis time of a 306^2 window holding a 260 px curve, with and without the free levels held.
int runFieldCost(const Args& args, Synthesizer& s) {
    auto c = std::make_shared<SynthesisConstraints>();
    CurveConstraint curve;
    curve.course = {{400.0, 500.0}, {512.0, 470.0}, {630.0, 520.0}};
    CurveWidget w;
    w.height_m = 1500.0f, w.left_gradient = -0.15f, w.right_gradient = -0.2f, w.left_reach_px = w.right_reach_px = 40.0f;
    curve.widgets = {w};
    c->curves.push_back(curve);
    for (int hold = 0; hold < 2; ++hold) {
        SynthesisParams params;
        params.constraints = c;
        params.hold_on_free_levels = hold != 0;
        std::vector<float> times;
        for (int k = 0; k < args.cases; ++k) {
            const double start = now();
            auto out = s.synthesize({360, 330, 306, 306}, params);
            if (!out) return 1;
            times.push_back(static_cast<float>(now() - start));
        }
        std::printf("hold %d: median %.1f ms\n", hold, 1000 * quantile(times, 0.5));
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    ::setenv("POCL_CACHE_DIR", TERRASYNTH_BENCH_POCL_CACHE, 0);
    Args args;
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string key = argv[i], value = argv[i + 1];
        if (key == "--db") args.db = value;
        else if (key == "--size") args.size = std::atoi(value.c_str());
        else if (key == "--cases") args.cases = std::atoi(value.c_str());
        else if (key == "--first") args.first = std::atoi(value.c_str());
        else if (key == "--spacing") args.spacing = std::atof(value.c_str());
        else if (key == "--rounds") args.rounds = std::atoi(value.c_str());
        else if (key == "--what") args.what = value;
        else return std::fprintf(stderr, "unknown option %s\n", key.c_str()), 2;
    }
    const std::string inputs =
        args.db == "shared" ? TERRASYNTH_BENCH_SHARED_EXEMPLARS : std::string(TERRASYNTH_BENCH_DATA_DIR) + "/exemplars";
    auto db = loadOrBuildDatabase({inputs}, {}, std::string(TERRASYNTH_BENCH_POCL_CACHE) + "/../bench_" + args.db + ".tsdb");
    if (!db) return std::fprintf(stderr, "%s\n", db.message().c_str()), 1;
    auto s = Synthesizer::create(db.value());
    if (!s) return std::fprintf(stderr, "%s\n", s.message().c_str()), 1;
    if (args.what == "detail") return runDetail(args, *s.value());
    if (args.what == "points") return runPoints(args, *s.value());
    if (args.what == "pastes") return runPastes(args, *s.value());
    if (args.what == "fieldcost") return runFieldCost(args, *s.value());
    return runCurves(args, *s.value());
}
