// Private: the properties of a curve constraint along its course (Gain et al. 2015 s3, s5.1):
// widget values interpolated by cubic Hermite curves in the arc-length parameter t, angular Hermite
// interpolation around the end caps, and junction height offsets. Implemented in curve_profile.cpp.
#pragma once

#include <vector>

#include "terrasynth/constraints.h"

namespace terrasynth::constraints {

// Heights in metres, gradients in metres per metre away from the course, reaches in level-0 pixels.
struct CurveProperties {
    double height = 0.0;
    double left_gradient = 0.0, right_gradient = 0.0;
    double left_reach = 0.0, right_reach = 0.0;
};

// Junction widget (s3, Figure 2c): pins the course's height at arc length `s` to `height`, blending
// the correction in and out over `blend_px` of arc length on either side.
struct JunctionPin {
    double s = 0.0;
    double height = 0.0;
    double blend_px = 1.0;
};

class CurveProfile {
public:
    // `widgets` need not be sorted; at least one (an empty list gives zero properties). `length` is
    // the course's arc length in level-0 pixels (t = s / length).
    CurveProfile(const std::vector<CurveWidget>& widgets, double length);

    // Widget interpolation at t (clamped to the first/last widget outside their range): cubic
    // Hermite per property with Catmull-Rom tangents over the widgets (finite differences over
    // the neighbouring widgets' t) and zero tangents at the first and last widget, so the profile
    // joins the constant extension with C1 continuity. Reaches are clamped to >= 0.
    CurveProperties widgetsAt(double t) const;

    // widgetsAt(s / length) plus the junction pins' height corrections.
    CurveProperties at(double s) const;

    // The height the widgets give at s and whether a widget sits within `snap_px` of arc length
    // of s (then that widget's height is returned: it "specifies" a junction there).
    double heightAt(double s) const { return widgetsAt(t(s)).height; }
    bool widgetNear(double s, double snap_px, double* height) const;

    // The curve's lift profile (CurveConstraint::lift_m): metres added to the target on the
    // constrained levels at s, linear between stations evenly spaced in t; 0 without one.
    void setLift(const std::vector<float>& lift) { lift_ = lift; }
    double liftAt(double s) const;

    // Replaces the junction pins; at() sums their corrections in this order. O(n log n).
    void setPins(std::vector<JunctionPin> pins);
    const std::vector<JunctionPin>& pins() const { return pins_; }
    double t(double s) const { return length_ > 0.0 ? s / length_ : 0.0; }
    double length() const { return length_; }

private:
    std::vector<CurveWidget> widgets_;
    std::vector<CurveProperties> values_, tangents_;  // per widget, tangents per unit t
    std::vector<JunctionPin> pins_;
    std::vector<float> lift_;
    // Per pin: the widgets' height at its arc length (what the pin corrects). The pins sorted by arc
    // length, so at() visits only those within reach: a long scribbled course has thousands.
    std::vector<double> pin_base_;
    std::vector<size_t> pins_by_s_;
    double max_blend_ = 0.0;
    double length_;
};

// End caps (s5.1: "angular Hermite interpolation of the left and right properties at the
// endpoints"): `leftness` in [0, 1] is the angle of the pixel around the endpoint, 0 on the right
// side line, 1/2 straight ahead, 1 on the left side line. Gradient and reach blend from the right
// value to the left with the Hermite basis 3a^2 - 2a^3 (zero angular derivative at both side lines,
// so the envelope joins the sides smoothly). Returned as both left and right fields.
CurveProperties capProperties(const CurveProperties& at_end, double leftness);

// Smooth bump for junction blending: 1 at 0, 0 from 1 on, C1 (Hermite).
double junctionFalloff(double u);

}  // namespace terrasynth::constraints
