// terrasynth/constraints.h: user control inside the synthesis (Gain et al. 2015 section 5).
//
// Point and curve constraints (s5.1, eq. 8-9) and type painting (s5.2) act inside the correction
// kernel, never as a post-hoc deformation, and are disabled on the finest two levels as in the
// paper, but for the geometric constraints' own pixels when their heights are held
// (SynthesisParams::hold_on_free_levels); freeze and pastes (s5.3) are driven through coherent
// re-synthesis (incremental.h).
// Coordinates are global pixels of level 0 (the project's grid); heights in metres.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "terrasynth/status.h"

namespace terrasynth {

struct ExemplarDatabase;

struct PointConstraint {
    double x = 0.0, y = 0.0;          // site, level-0 global pixels (x east, y south)
    float height_m = 0.0f;            // target height at the site
    float slope_direction_deg = 0.0f; // direction the ground rises towards, clockwise from north
    float slope_angle_deg = 0.0f;     // 0..80; the target plane rises at tan(angle) m per m
    float radius_px = 64.0f;          // area of effect, level-0 pixels (> 0)
    // Metres added to the target on the constrained levels so the finished site lands on height_m
    // although the finest levels are unconstrained (set by liftPointConstraints in synthesizer.h;
    // not read from projects). 0 = the paper's plain target.
    float lift_m = 0.0f;
    // Metres per metre added to the target plane's rise towards the east and the south within the
    // site's 7x7 pixels (fading out by twice that distance), so the slope seen over the site's own
    // pixels holds too (set by liftPointConstraints when the free levels hold the site; not read
    // from projects). 0 = none.
    float tilt_east = 0.0f, tilt_south = 0.0f;
    // Metres per metre added to the rise towards the east and the south over the rest of the radius
    // (beyond the site's pixels, where tilt_east/south fade out), so the slope seen over half the
    // radius holds too: around a small point asking a gentle slope against steep terrain, eq. 8-9
    // pull each pixel only halfway from what its unconstrained neighbours ask (set by
    // liftPointConstraints like the tilts; not read from projects). 0 = none.
    float wide_tilt_east = 0.0f, wide_tilt_south = 0.0f;

    // Equal in everything the user sets (the lifts excluded).
    bool samePlacement(const PointConstraint& o) const {
        return x == o.x && y == o.y && height_m == o.height_m && slope_direction_deg == o.slope_direction_deg &&
               slope_angle_deg == o.slope_angle_deg && radius_px == o.radius_px;
    }
    bool sameLifts(const PointConstraint& o) const {
        return lift_m == o.lift_m && tilt_east == o.tilt_east && tilt_south == o.tilt_south &&
               wide_tilt_east == o.wide_tilt_east && wide_tilt_south == o.wide_tilt_south;
    }
    void takeLifts(const PointConstraint& o) {
        lift_m = o.lift_m, tilt_east = o.tilt_east, tilt_south = o.tilt_south;
        wide_tilt_east = o.wide_tilt_east, wide_tilt_south = o.wide_tilt_south;
    }
};

// A widget on a curve constraint (s3, s5.1): properties at arc-length parameter t of the course.
// Gradients are the rise of the ground in metres per metre going away from the curve on that side
// (negative = the ground falls away, e.g. a ridge; a cliff top has 0 on one side and a large negative
// value on the other). Reaches are the area of effect on each side in level-0 pixels.
struct CurveWidget {
    double t = 0.0;                // 0..1 along the course (arc length)
    float height_m = 0.0f;
    float left_gradient = 0.0f, right_gradient = 0.0f;
    float left_reach_px = 32.0f, right_reach_px = 32.0f;
};

// A curve constraint: a course (polyline in level-0 global pixels, optionally smoothed as a
// Catmull-Rom spline) with widgets interpolated by Hermite curves along it. Left is the left of the
// direction of travel (x east, y south: left of a course heading east is north).
struct CurveConstraint {
    std::vector<std::pair<double, double>> course;
    bool spline = true;
    std::vector<CurveWidget> widgets;  // at least one; sorted by t
    // Lift profile: metres added to the course's height (and so to the whole target across the
    // reach) on the constrained levels, so the finished course lands on the widgets' heights
    // although the finest levels are free. Values at n >= 2 stations evenly spaced in t
    // (t = k / (n - 1)), linear in between; set by liftCurveConstraints (synthesizer.h), not read
    // from projects. Empty = the paper's plain targets.
    std::vector<float> lift_m;
};

// Paper defaults of eq. 8: tolerance slope s and outer slope lambda of phi_d.
constexpr float kPointToleranceSlope = 0.5f;
constexpr float kPointBlendSlope = 0.5f;
// s5.1: the area of effect at level i is min(reach, kPointLocalisation * 2^i) level-0 pixels. Curves
// keep it; points act over their whole radius on every constrained level (the tolerance of phi_d
// grows with the distance, so that only pulls terrain that strays far from the asked plane), which
// holds their slope direction over the radius (docs/realism.md).
constexpr float kPointLocalisation = 4.0f;
// Geometric and type constraints act on levels >= this (s5.1, s5.2: off on the finest two).
constexpr int kFirstConstrainedLevel = 2;
// Type painting stores target sets as 32-bit masks: databases with more types cannot be painted.
constexpr int kMaxPaintableTypes = 32;
// Seeding (s5.2): candidates drawn per target type when every regular candidate is rejected.
constexpr int kSeedsPerType = 9;

// Painted target type per level-0 pixel over a rectangle of the global grid. kUnpainted = any type.
struct TypePaint {
    static constexpr uint8_t kUnpainted = 255;
    int64_t x = 0, y = 0;
    int width = 0, height = 0;
    std::vector<uint8_t> types;  // width*height database type ids or kUnpainted

    bool empty() const { return types.empty(); }
};

// Copy-paste (s5.3, fig. 8): the polygon `source` (level-0 pixels of the terrain's grid, or of
// exemplar `exemplar` when >= 0) moved by (dx, dy) and raised by `height_offset_m`, then frozen.
struct PasteConstraint {
    std::vector<std::pair<double, double>> source;
    int exemplar = -1;
    double dx = 0.0, dy = 0.0;
    float height_offset_m = 0.0f;
};

struct SynthesisConstraints {
    std::vector<PointConstraint> points;
    std::vector<CurveConstraint> curves;
    TypePaint types;
    // Not used by the correction kernel itself but by whoever drives coherent re-synthesis
    // (terrasynth/incremental.h, Terrain): the freeze brush (1 = frozen, over `freeze` rectangle)
    // and pastes, applied in order.
    TypePaint freeze;
    std::vector<PasteConstraint> pastes;
    bool empty() const { return points.empty() && curves.empty() && types.empty() && freeze.empty() && pastes.empty(); }
    bool shapesTerrain() const { return !points.empty() || !curves.empty() || !types.empty(); }
};

// Paints a round brush of `radius_px` (> 0) level-0 pixels with `value` along the polyline `line`
// (global level-0 pixels), clipped to the paint's rectangle: the type and freeze brushes of s5.2-5.3.
// Dabs are stamped at most max(0.5, radius/2) pixels apart; only those that reach the rectangle
// cost anything, so the work is what strokePaintCost says.
void paintStroke(TypePaint& paint, const std::vector<std::pair<double, double>>& line, double radius_px,
                 uint8_t value);
// The work paintStroke will do, in pixel rows visited (dabs reaching the rectangle times their rows,
// plus one pass over the rectangle), computed in O(line.size()): projects refuse strokes above
// limits::kMaxStrokePaintCost.
uint64_t strokePaintCost(const TypePaint& paint, const std::vector<std::pair<double, double>>& line, double radius_px);

// Parses the "constraints" object of a project (JSON text, docs/project-format.md) against the
// database's type and exemplar names. `extent_*` is the project's extent: coordinates in the JSON are
// relative to its origin, masks and strokes paint over it; mask paths are relative to `base_dir`.
// Errors name the field: "constraints.points[1].radius_px: must be in [0.001, 1000000], got 0".
Result<SynthesisConstraints> parseConstraints(const std::string& constraints_json, const std::string& base_dir,
                                              const ExemplarDatabase& db, int64_t extent_x, int64_t extent_y,
                                              int extent_width, int extent_height);

// The inverse of parseConstraints: the "constraints" object for `constraints` over the same extent,
// with type painting and the freeze brush as 8-bit mask PNGs ("<mask_stem>.types.png" with a palette
// naming type id + 1, "<mask_stem>.freeze.png" with 255 = frozen) that the caller writes beside the
// project, so parseConstraints(constraintsToJson(c).json) == c up to the last bit of coordinates that
// are not whole pixels. Point and curve lifts (lift_m) are not part of a project and are not written.
// Errors: a type or exemplar index the database does not have.
struct ConstraintsJson {
    std::string json;  // the "constraints" object, compact JSON text
    struct Mask {
        std::string file;  // mask_stem + suffix; the JSON names its base name (relative to the project)
        int width = 0, height = 0;
        std::vector<uint8_t> pixels;  // 8-bit gray, row-major
    };
    std::vector<Mask> masks;
};
Result<ConstraintsJson> constraintsToJson(const SynthesisConstraints& constraints, const ExemplarDatabase& db,
                                          int64_t extent_x, int64_t extent_y, int extent_width, int extent_height,
                                          const std::string& mask_stem);

}  // namespace terrasynth
