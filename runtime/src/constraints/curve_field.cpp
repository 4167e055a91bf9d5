// Curve constraints (Gain et al. 2015 s5.1) rasterised into the correction kernel's blend sums.
#include "constraints/curve_field.h"

#include <cmath>
#include <mutex>

#include "constraints/curve_geometry.h"
#include "constraints/curve_junctions.h"
#include "constraints/curve_raster.h"
#include "core/number_text.h"

namespace terrasynth::constraints {
namespace {

// The courses' samplings and their crossings, cached by the samplings' identity: a synthesis asks
// for every level and every window with the same courses.
struct PreparedCourses {
    std::vector<std::shared_ptr<const CourseSamples>> courses;
    std::shared_ptr<const CrossingSearch> crossings;
};

PreparedCourses prepareCourses(const std::vector<CurveConstraint>& curves) {
    PreparedCourses out;
    std::vector<const CourseSamples*> raw;
    for (const CurveConstraint& curve : curves) {
        out.courses.push_back(cachedCourse(curve));
        raw.push_back(out.courses.back().get());
    }
    static std::mutex mutex;
    static std::vector<std::weak_ptr<const CourseSamples>> last_courses;
    static std::shared_ptr<const CrossingSearch> last_crossings;
    {
        std::lock_guard<std::mutex> lock(mutex);
        bool same = last_crossings && last_courses.size() == out.courses.size();
        for (size_t i = 0; same && i < out.courses.size(); ++i) same = last_courses[i].lock() == out.courses[i];
        if (same) {
            out.crossings = last_crossings;
            return out;
        }
    }
    out.crossings = std::make_shared<const CrossingSearch>(findCrossings(raw));
    std::lock_guard<std::mutex> lock(mutex);
    last_courses.assign(out.courses.begin(), out.courses.end());
    last_crossings = out.crossings;
    return out;
}

}  // namespace

PinnedCurves pinCurves(const std::vector<CurveConstraint>& curves) {
    // Courses are cached by their points (the distance field's geometry changes only when the
    // horizontal shape does); widgets, lifts and junction heights are cheap and rebuilt per call.
    const PreparedCourses prepared = prepareCourses(curves);
    PinnedCurves pinned;
    pinned.courses = prepared.courses;
    for (size_t i = 0; i < curves.size(); ++i) {
        pinned.profiles.emplace_back(curves[i].widgets, prepared.courses[i]->length);
        pinned.profiles.back().setLift(curves[i].lift_m);
    }
    pinJunctions(prepared.crossings->crossings, pinned.profiles);
    return pinned;
}

void accumulateCurves(const std::vector<CurveConstraint>& curves, int level, const core::LevelRegion& region,
                      double meters_per_pixel0, std::vector<float>& sums, bool held_free_level) {
    TERRASYNTH_REQUIRE(sums.size() == 3 * region.pixels(), "accumulateCurves: sums must hold 3 floats per region pixel");
    if (curves.empty()) return;
    const PinnedCurves pinned = pinCurves(curves);
    for (size_t i = 0; i < curves.size(); ++i)
        accumulateCurve(*pinned.courses[i], pinned.profiles[i], level, region, meters_per_pixel0, true, sums,
                        held_free_level);
}

Status checkCurveLimits(const std::vector<CurveConstraint>& curves, const std::string& where) {
    if (curves.size() > static_cast<size_t>(limits::kMaxCurves))
        return Status::error(where + ": " + std::to_string(curves.size()) + " curves, at most " + std::to_string(limits::kMaxCurves));
    const double bound = static_cast<double>(limits::kMaxWindowOrigin);
    double total_length = 0.0;
    for (size_t i = 0; i < curves.size(); ++i) {
        const CurveConstraint& c = curves[i];
        const std::string name = where + "[" + std::to_string(i) + "]";
        if (c.course.size() > static_cast<size_t>(limits::kMaxCoursePoints))
            return Status::error(name + ".course: " + std::to_string(c.course.size()) + " points, at most " +
                                 std::to_string(limits::kMaxCoursePoints));
        if (c.widgets.empty() || c.widgets.size() > static_cast<size_t>(limits::kMaxCurveWidgets))
            return Status::error(name + ".widgets: 1.." + std::to_string(limits::kMaxCurveWidgets) + " widgets");
        for (size_t k = 0; k < c.course.size(); ++k) {
            const auto& [x, y] = c.course[k];
            if (!(std::fabs(x) <= bound && std::fabs(y) <= bound))
                return Status::error(name + ".course[" + std::to_string(k) + "]: beyond +-2^29 pixels of the global grid");
            if (k > 0) total_length += std::hypot(x - c.course[k - 1].first, y - c.course[k - 1].second);
        }
        if (total_length > limits::kMaxTotalCourseLengthPx)
            return Status::error(name + ".course: the courses are " + detail::compactNumber(total_length) +
                                 " pixels long together, at most " + detail::compactNumber(limits::kMaxTotalCourseLengthPx));
    }
    const PreparedCourses prepared = prepareCourses(curves);
    if (!prepared.crossings->complete)
        return Status::error(where + ": the courses cross each other more than " + std::to_string(limits::kMaxJunctions) +
                             " times (or pile up on each other); simplify them");
    return Status::ok();
}

}  // namespace terrasynth::constraints
