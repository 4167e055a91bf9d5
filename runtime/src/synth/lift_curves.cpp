// Curve heights that hold although the finest levels are free (s5.1 + windowed determinism): the
// curve equivalent of lift_points.cpp.
//
// The paper disables geometric constraints on the finest two levels; their detail then moves the
// finished course away from the widgets' heights (measured: a median 3-4% of the relief). A lift
// profile along the course (stations evenly spaced in t, linear in between) is added to the target
// on the constrained levels; each station's residual is the finished course's residual averaged
// around it with the interpolation's own weights, measured on windows along the course, and each
// station is searched like a point lift. Inside the kernels the curve still acts only through phi_d.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "constraints/curve_field.h"
#include "synth/lift_search.h"
#include "terrasynth/synthesizer.h"

namespace terrasynth {
namespace {

// Windows along the course are cut from tiles of the global grid this big: big enough that the
// synthesis margins (16 px per level) do not dominate, small enough to stay close to the course.
constexpr int64_t kProbeTilePx = 64;

// One point of a course where the finished height is compared with the widgets' height.
struct CourseProbe {
    size_t curve = 0;
    double x = 0.0, y = 0.0;
    double target = 0.0;  // widgets' height with the junctions pinned, metres
    size_t station = 0;   // the probe lies between stations `station` and `station + 1`
    double weight = 0.0;  // of station + 1; station gets 1 - weight
    float finished = 0.0f;
};

size_t stationCount(double length, double spacing) {
    return std::max<size_t>(2, static_cast<size_t>(std::lround(length / spacing)) + 1);
}

// A lift profile carried over to `n` stations (linear in t), so a search can start from it.
std::vector<float> resampledLift(const std::vector<float>& lift, size_t n) {
    if (lift.size() == n) return lift;
    std::vector<float> out(n, lift.size() == 1 ? lift[0] : 0.0f);
    if (lift.size() < 2) return out;
    for (size_t k = 0; k < n; ++k) {
        const double x = static_cast<double>(k) / static_cast<double>(n - 1) * static_cast<double>(lift.size() - 1);
        const size_t i = std::min(static_cast<size_t>(x), lift.size() - 2);
        out[k] = static_cast<float>(lift[i] + (static_cast<double>(lift[i + 1]) - lift[i]) * (x - static_cast<double>(i)));
    }
    return out;
}

// Position of arc length s on the sampled course.
std::pair<double, double> courseAt(const constraints::CourseSamples& c, double s) {
    const size_t i = static_cast<size_t>(std::upper_bound(c.s.begin(), c.s.end(), s) - c.s.begin());
    if (i == 0) return {c.x.front(), c.y.front()};
    if (i >= c.s.size()) return {c.x.back(), c.y.back()};
    const double span = c.s[i] - c.s[i - 1], u = span > 0.0 ? (s - c.s[i - 1]) / span : 0.0;
    return {c.x[i - 1] + (c.x[i] - c.x[i - 1]) * u, c.y[i - 1] + (c.y[i] - c.y[i - 1]) * u};
}

// Bilinear height of level-0 field `h` (pixel (0, 0) at global (x0, y0)) at global (x, y); false
// where the field does not hold the 2x2 pixels around it.
bool finishedAt(const Heightfield& h, int64_t x0, int64_t y0, double x, double y, float* out) {
    const double fx = std::floor(x), fy = std::floor(y);
    const int64_t ix = static_cast<int64_t>(fx) - x0, iy = static_cast<int64_t>(fy) - y0;
    if (ix < 0 || iy < 0 || ix + 1 >= h.width || iy + 1 >= h.height) return false;
    const int cx = static_cast<int>(ix), cy = static_cast<int>(iy);
    const float tx = static_cast<float>(x - fx), ty = static_cast<float>(y - fy);
    const float top = h.at(cx, cy) + (h.at(cx + 1, cy) - h.at(cx, cy)) * tx;
    const float bottom = h.at(cx, cy + 1) + (h.at(cx + 1, cy + 1) - h.at(cx, cy + 1)) * tx;
    *out = top + (bottom - top) * ty;
    return true;
}

// Finished level-0 heights at every probe: read from `measured` where it holds them, otherwise from
// one synthesis per tile of the global grid holding probes (the window is their bounding box).
Status measureProbes(Synthesizer& synthesizer, const SynthesisParams& params, const CurveLiftOptions& measured,
                     std::vector<CourseProbe>& probes) {
    std::map<std::pair<int64_t, int64_t>, std::vector<size_t>> tiles;
    auto tileOf = [](double v) { return static_cast<int64_t>(std::floor(std::floor(v) / kProbeTilePx)); };
    for (size_t i = 0; i < probes.size(); ++i)
        if (!measured.measured || !finishedAt(*measured.measured, measured.measured_x, measured.measured_y, probes[i].x,
                                               probes[i].y, &probes[i].finished))
            tiles[{tileOf(probes[i].x), tileOf(probes[i].y)}].push_back(i);
    for (const auto& [tile, members] : tiles) {
        int64_t x0 = INT64_MAX, y0 = INT64_MAX, x1 = INT64_MIN, y1 = INT64_MIN;
        for (size_t i : members) {
            const int64_t fx = static_cast<int64_t>(std::floor(probes[i].x)), fy = static_cast<int64_t>(std::floor(probes[i].y));
            x0 = std::min(x0, fx), y0 = std::min(y0, fy), x1 = std::max(x1, fx + 1), y1 = std::max(y1, fy + 1);
        }
        const PixelWindow window{x0, y0, static_cast<int>(x1 - x0 + 1), static_cast<int>(y1 - y0 + 1)};
        auto out = synthesizer.synthesize(window, params, 0, false);
        if (!out) return out.status();
        for (size_t i : members) finishedAt(out->heights, x0, y0, probes[i].x, probes[i].y, &probes[i].finished);
    }
    return Status::ok();
}

float medianOf(std::vector<float> v) {
    if (v.empty()) return 0.0f;
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return v[v.size() / 2];
}

// The stations of one curve and their searches.
struct CurveStations {
    size_t curve = 0;
    bool closed = false;
    std::vector<bool> moving;
    std::vector<synth::LiftSearch> searches;
    std::vector<float> best;
};

}  // namespace

Result<std::shared_ptr<const SynthesisConstraints>> liftCurveConstraints(Synthesizer& synthesizer,
                                                                         const SynthesisParams& params,
                                                                         const CurveLiftOptions& options) {
    TERRASYNTH_REQUIRE(options.max_rounds >= 1 && options.tolerance_m >= 0.0f && options.station_spacing_px > 0.0,
                       "liftCurveConstraints: bad options");
    if (!params.constraints || params.constraints->curves.empty()) return params.constraints;
    auto lifted = std::make_shared<SynthesisConstraints>(*params.constraints);
    std::vector<CurveConstraint>& curves = lifted->curves;
    const constraints::PinnedCurves pinned = constraints::pinCurves(curves);

    // Stations (moving ones: in the window) and the probes that inform them.
    std::vector<CurveStations> stations;
    std::vector<CourseProbe> probes;
    bool resampled = false;
    for (size_t c = 0; c < curves.size(); ++c) {
        const constraints::CourseSamples& course = *pinned.courses[c];
        if (course.segments() == 0) continue;
        const size_t n = stationCount(course.length, options.station_spacing_px);
        CurveStations st;
        st.curve = c;
        st.closed = course.closed;
        st.moving.assign(n, false);
        bool any = false;
        for (size_t k = 0; k < n; ++k) {
            const auto [x, y] = courseAt(course, course.length * static_cast<double>(k) / static_cast<double>(n - 1));
            const std::optional<PixelWindow>& w = options.stations_within;
            st.moving[k] = !w || w->contains(static_cast<int64_t>(std::floor(x)), static_cast<int64_t>(std::floor(y)));
            any = any || st.moving[k];
        }
        if (!any) continue;
        resampled = resampled || curves[c].lift_m.size() != n;
        curves[c].lift_m = resampledLift(curves[c].lift_m, n);
        for (size_t i = 0; i < course.x.size(); ++i) {
            const double x = course.s[i] / course.length * static_cast<double>(n - 1);
            const size_t k = std::min(static_cast<size_t>(x), n - 2);
            if (!st.moving[k] && !st.moving[k + 1]) continue;
            CourseProbe p;
            p.curve = c;
            p.x = course.x[i], p.y = course.y[i];
            p.target = pinned.profiles[c].at(course.s[i]).height;
            p.station = k;
            p.weight = x - static_cast<double>(k);
            probes.push_back(p);
        }
        st.searches.resize(n);
        st.best = curves[c].lift_m;
        stations.push_back(std::move(st));
    }
    if (stations.empty()) return params.constraints;

    SynthesisParams probe = params;
    probe.record_history = false;
    probe.constraints = lifted;
    float best_score = std::numeric_limits<float>::infinity();
    int best_round = -1;
    std::vector<size_t> station_of_curve(curves.size(), SIZE_MAX);
    for (size_t i = 0; i < stations.size(); ++i) station_of_curve[stations[i].curve] = i;
    for (int round = 0; round < options.max_rounds; ++round) {
        // Heights synthesized already are the given lifts' only (the first round, nothing resampled).
        CurveLiftOptions given;
        if (round == 0 && !resampled) given = options;
        if (Status s = measureProbes(synthesizer, probe, given, probes); !s) return s.withContext("curve constraints");
        // Per station: the residual averaged with the interpolation's weights.
        std::vector<std::vector<double>> sum(stations.size()), weight(stations.size());
        for (size_t i = 0; i < stations.size(); ++i) {
            sum[i].assign(stations[i].moving.size(), 0.0);
            weight[i].assign(stations[i].moving.size(), 0.0);
        }
        std::vector<float> misses;
        misses.reserve(probes.size());
        double total = 0.0;
        for (const CourseProbe& p : probes) {
            const size_t i = station_of_curve[p.curve];
            const double r = static_cast<double>(p.finished) - p.target;
            total += std::fabs(r);
            misses.push_back(static_cast<float>(std::fabs(r)));
            sum[i][p.station] += (1.0 - p.weight) * r, weight[i][p.station] += 1.0 - p.weight;
            sum[i][p.station + 1] += p.weight * r, weight[i][p.station + 1] += p.weight;
        }
        // The lifts of a whole round were synthesized together, so the best round is what is kept.
        const float score = static_cast<float>(total / static_cast<double>(probes.size()));
        if (score < best_score) {
            best_score = score, best_round = round;
            for (CurveStations& st : stations) st.best = curves[st.curve].lift_m;
        }
        if (medianOf(std::move(misses)) <= options.tolerance_m || round + 1 == options.max_rounds) break;
        for (size_t i = 0; i < stations.size(); ++i) {
            CurveStations& st = stations[i];
            const size_t n = st.moving.size();
            if (st.closed) {
                // The first and last stations are one place: one residual, one lift.
                sum[i][0] = sum[i][n - 1] = sum[i][0] + sum[i][n - 1];
                weight[i][0] = weight[i][n - 1] = weight[i][0] + weight[i][n - 1];
            }
            std::vector<float>& lift = curves[st.curve].lift_m;
            for (size_t k = 0; k < n; ++k) {
                if (!st.moving[k] || weight[i][k] <= 0.0) continue;
                st.searches[k].record(lift[k], static_cast<float>(sum[i][k] / weight[i][k]), round);
                lift[k] = st.searches[k].next();
            }
            if (st.closed) lift.back() = lift.front();
        }
    }
    // Unchanged lifts give back the given constraints, so a caller can keep what it synthesized.
    if (best_round == 0 && !resampled) return params.constraints;
    for (CurveStations& st : stations) curves[st.curve].lift_m = st.best;
    return std::shared_ptr<const SynthesisConstraints>(std::move(lifted));
}

}  // namespace terrasynth
