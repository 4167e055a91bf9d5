// The course of a curve constraint as the kernels see it (terrasynth/curve_course.h).
#include "terrasynth/curve_course.h"

#include <algorithm>
#include <cmath>

#include "constraints/curve_field.h"

namespace terrasynth {

std::vector<CurveCourseSample> sampleCurveCourse(const std::vector<CurveConstraint>& curves, size_t index,
                                                 double step_px) {
    TERRASYNTH_REQUIRE(index < curves.size(), "sampleCurveCourse: no such curve");
    TERRASYNTH_REQUIRE(step_px > 0.0, "sampleCurveCourse: step must be > 0");
    const constraints::PinnedCurves pinned = constraints::pinCurves(curves);
    const constraints::CourseSamples& c = *pinned.courses[index];
    const constraints::CurveProfile& profile = pinned.profiles[index];
    std::vector<CurveCourseSample> out;
    if (c.segments() == 0) return out;
    const size_t count = static_cast<size_t>(std::ceil(c.length / step_px)) + 1;
    size_t segment = 0;
    for (size_t k = 0; k < count; ++k) {
        const double s = std::min(c.length, static_cast<double>(k) * step_px);
        while (segment + 1 < c.segments() && c.s[segment + 1] < s) ++segment;
        const double span = c.s[segment + 1] - c.s[segment];
        const double u = span > 0.0 ? std::clamp((s - c.s[segment]) / span, 0.0, 1.0) : 0.0;
        const double ex = c.x[segment + 1] - c.x[segment], ey = c.y[segment + 1] - c.y[segment];
        const double len = std::hypot(ex, ey);
        CurveCourseSample sample;
        sample.x = c.x[segment] + u * ex;
        sample.y = c.y[segment] + u * ey;
        sample.s = s;
        sample.t = profile.t(s);
        sample.left_x = len > 0.0 ? ey / len : 0.0;  // left of travel (see curve_raster.cpp)
        sample.left_y = len > 0.0 ? -ex / len : 0.0;
        const constraints::CurveProperties p = profile.at(s);
        sample.height_m = static_cast<float>(p.height);
        sample.left_gradient = static_cast<float>(p.left_gradient);
        sample.right_gradient = static_cast<float>(p.right_gradient);
        sample.left_reach_px = static_cast<float>(p.left_reach);
        sample.right_reach_px = static_cast<float>(p.right_reach);
        sample.lift_m = static_cast<float>(profile.liftAt(s));
        out.push_back(sample);
        if (s >= c.length) break;
    }
    return out;
}

namespace {

// Bilinear height at a level-0 global position; false outside the field.
bool heightAt(const Heightfield& h, int64_t origin_x, int64_t origin_y, double x, double y, double* out) {
    const double fx = std::floor(x), fy = std::floor(y);
    const int64_t ix = static_cast<int64_t>(fx) - origin_x, iy = static_cast<int64_t>(fy) - origin_y;
    if (ix < 0 || iy < 0 || ix + 1 >= h.width || iy + 1 >= h.height) return false;
    const int cx = static_cast<int>(ix), cy = static_cast<int>(iy);
    const double tx = x - fx, ty = y - fy;
    const double top = h.at(cx, cy) + (static_cast<double>(h.at(cx + 1, cy)) - h.at(cx, cy)) * tx;
    const double bottom = h.at(cx, cy + 1) + (static_cast<double>(h.at(cx + 1, cy + 1)) - h.at(cx, cy + 1)) * tx;
    *out = top + (bottom - top) * ty;
    return true;
}

}  // namespace

CurveHold measureCurveHold(const Heightfield& heights, int64_t origin_x, int64_t origin_y,
                           const std::vector<CurveConstraint>& curves, size_t index, double meters_per_pixel) {
    TERRASYNTH_REQUIRE(meters_per_pixel > 0.0, "measureCurveHold: spacing must be > 0");
    CurveHold hold;
    for (const CurveCourseSample& c : sampleCurveCourse(curves, index, 1.0)) {
        double on = 0.0;
        if (!heightAt(heights, origin_x, origin_y, c.x, c.y, &on)) continue;
        hold.height_error_m.push_back(static_cast<float>(on - c.height_m));
        for (int side = 0; side < 2; ++side) {
            const double reach = side == 0 ? c.left_reach_px : c.right_reach_px;
            if (reach < 4.0) continue;
            const double d = 0.5 * reach, sign = side == 0 ? 1.0 : -1.0;
            double off = 0.0;
            if (!heightAt(heights, origin_x, origin_y, c.x + sign * c.left_x * d, c.y + sign * c.left_y * d, &off)) continue;
            const double asked = side == 0 ? c.left_gradient : c.right_gradient;
            hold.gradient_error.push_back(static_cast<float>((off - on) / (d * meters_per_pixel) - asked));
        }
    }
    return hold;
}

}  // namespace terrasynth
