// Curve constraint properties along the course (Gain et al. 2015 s3: "We interpolate the widget
// values to derive attributes elsewhere on the constraint curve, using Hermite curves").
#include "constraints/curve_profile.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace terrasynth::constraints {
namespace {

CurveProperties valuesOf(const CurveWidget& w) {
    return {w.height_m, w.left_gradient, w.right_gradient, w.left_reach_px, w.right_reach_px};
}

CurveProperties combine(const CurveProperties& a, double wa, const CurveProperties& b, double wb) {
    return {a.height * wa + b.height * wb, a.left_gradient * wa + b.left_gradient * wb,
            a.right_gradient * wa + b.right_gradient * wb, a.left_reach * wa + b.left_reach * wb,
            a.right_reach * wa + b.right_reach * wb};
}

double smoothstep(double a) {
    a = std::clamp(a, 0.0, 1.0);
    return a * a * (3.0 - 2.0 * a);
}

}  // namespace

CurveProfile::CurveProfile(const std::vector<CurveWidget>& widgets, double length) : widgets_(widgets), length_(length) {
    std::stable_sort(widgets_.begin(), widgets_.end(), [](const CurveWidget& a, const CurveWidget& b) { return a.t < b.t; });
    const size_t n = widgets_.size();
    for (const CurveWidget& w : widgets_) values_.push_back(valuesOf(w));
    tangents_.assign(n, CurveProperties{});
    // Catmull-Rom tangents over non-uniformly spaced widgets; the end widgets keep zero tangents.
    for (size_t k = 1; k + 1 < n; ++k) {
        const double span = widgets_[k + 1].t - widgets_[k - 1].t;
        if (span > 1e-12) tangents_[k] = combine(values_[k + 1], 1.0 / span, values_[k - 1], -1.0 / span);
    }
}

CurveProperties CurveProfile::widgetsAt(double t) const {
    if (widgets_.empty()) return {};
    CurveProperties p;
    if (t <= widgets_.front().t) {
        p = values_.front();
    } else if (t >= widgets_.back().t) {
        p = values_.back();
    } else {
        const size_t k = static_cast<size_t>(
            std::upper_bound(widgets_.begin(), widgets_.end(), t, [](double v, const CurveWidget& w) { return v < w.t; }) -
            widgets_.begin() - 1);
        const double h = widgets_[k + 1].t - widgets_[k].t;
        if (h <= 1e-12) {
            p = values_[k + 1];
        } else {
            const double u = (t - widgets_[k].t) / h, u2 = u * u, u3 = u2 * u;
            const double h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
            p = combine(combine(values_[k], h00, tangents_[k], h10 * h), 1.0,
                        combine(values_[k + 1], h01, tangents_[k + 1], h11 * h), 1.0);
        }
    }
    p.left_reach = std::max(0.0, p.left_reach);
    p.right_reach = std::max(0.0, p.right_reach);
    return p;
}

void CurveProfile::setPins(std::vector<JunctionPin> pins) {
    pins_ = std::move(pins);
    pin_base_.clear();
    max_blend_ = 0.0;
    for (const JunctionPin& pin : pins_) {
        pin_base_.push_back(heightAt(pin.s));
        max_blend_ = std::max(max_blend_, pin.blend_px);
    }
    pins_by_s_.resize(pins_.size());
    std::iota(pins_by_s_.begin(), pins_by_s_.end(), size_t(0));
    std::stable_sort(pins_by_s_.begin(), pins_by_s_.end(), [&](size_t a, size_t b) { return pins_[a].s < pins_[b].s; });
}

CurveProperties CurveProfile::at(double s) const {
    CurveProperties p = widgetsAt(t(s));
    if (pins_.empty()) return p;
    // A pin acts within its blend distance only (the falloff is exactly 0 from there on). The pins
    // that may reach s are found by arc length (with a margin for rounding) and added in the order
    // they were pinned, so the sum is bit for bit the one over every pin.
    const double reach = max_blend_ * (1.0 + 1e-9) + 1e-9;
    const auto first = std::lower_bound(pins_by_s_.begin(), pins_by_s_.end(), s - reach,
                                        [&](size_t k, double v) { return pins_[k].s < v; });
    const auto last = std::upper_bound(first, pins_by_s_.end(), s + reach,
                                       [&](double v, size_t k) { return v < pins_[k].s; });
    std::vector<size_t> near(first, last);
    std::sort(near.begin(), near.end());
    for (size_t k : near) {
        const JunctionPin& pin = pins_[k];
        const double w = junctionFalloff(std::abs(s - pin.s) / pin.blend_px);
        if (w > 0.0) p.height += w * (pin.height - pin_base_[k]);
    }
    return p;
}

double CurveProfile::liftAt(double s) const {
    if (lift_.empty()) return 0.0;
    if (lift_.size() == 1) return lift_[0];
    const double x = std::clamp(t(s), 0.0, 1.0) * static_cast<double>(lift_.size() - 1);
    const size_t k = std::min(static_cast<size_t>(x), lift_.size() - 2);
    const double u = x - static_cast<double>(k);
    return lift_[k] + (static_cast<double>(lift_[k + 1]) - lift_[k]) * u;
}

bool CurveProfile::widgetNear(double s, double snap_px, double* height) const {
    // Widgets are sorted by t, so w.t * length - s grows along them: the first widget not more than
    // snap_px before s is the only one that can be (and the first that is) within snap_px.
    const auto it = std::partition_point(widgets_.begin(), widgets_.end(),
                                         [&](const CurveWidget& w) { return w.t * length_ - s < -snap_px; });
    if (it == widgets_.end() || std::abs(it->t * length_ - s) > snap_px) return false;
    *height = it->height_m;
    return true;
}

CurveProperties capProperties(const CurveProperties& at_end, double leftness) {
    const double w = smoothstep(leftness);
    CurveProperties p = at_end;
    p.left_gradient = p.right_gradient = at_end.right_gradient + (at_end.left_gradient - at_end.right_gradient) * w;
    p.left_reach = p.right_reach = at_end.right_reach + (at_end.left_reach - at_end.right_reach) * w;
    return p;
}

double junctionFalloff(double u) { return 1.0 - smoothstep(u); }

}  // namespace terrasynth::constraints
