// Perspective canvas of s4.1: a ground-plane homography from the artist's grid lines, and silhouette
// strokes turned into ridges on the heightfield.
#include <algorithm>
#include <cmath>
#include <string>

#include "terrasynth/layers_tools.h"

namespace terrasynth {
namespace {

double cross(Point2 o, Point2 a, Point2 b) { return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x); }

bool anyThreeCollinear(const std::array<Point2, 4>& p) {
    double scale = 0;
    for (auto& q : p) scale = std::max({scale, std::fabs(q.x), std::fabs(q.y), 1.0});
    for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j)
            for (int k = j + 1; k < 4; ++k)
                if (std::fabs(cross(p[i], p[j], p[k])) < 1e-9 * scale * scale) return true;
    return false;
}

// Solves A x = b (n x n, row-major) by Gaussian elimination with partial pivoting.
bool solveLinear(std::vector<double>& a, std::vector<double>& b, int n) {
    for (int c = 0; c < n; ++c) {
        int piv = c;
        for (int r = c + 1; r < n; ++r)
            if (std::fabs(a[r * n + c]) > std::fabs(a[piv * n + c])) piv = r;
        if (std::fabs(a[piv * n + c]) < 1e-12) return false;
        if (piv != c) {
            for (int k = 0; k < n; ++k) std::swap(a[c * n + k], a[piv * n + k]);
            std::swap(b[c], b[piv]);
        }
        for (int r = c + 1; r < n; ++r) {
            const double f = a[r * n + c] / a[c * n + c];
            for (int k = c; k < n; ++k) a[r * n + k] -= f * a[c * n + k];
            b[r] -= f * b[c];
        }
    }
    for (int r = n - 1; r >= 0; --r) {
        double s = b[r];
        for (int k = r + 1; k < n; ++k) s -= a[r * n + k] * b[k];
        b[r] = s / a[r * n + r];
    }
    return true;
}

double horizonV(const Line2& h, double u) {
    return h.a.y + (u - h.a.x) * (h.b.y - h.a.y) / (h.b.x - h.a.x);
}

bool finitePoint(Point2 p) { return std::isfinite(p.x) && std::isfinite(p.y); }

}  // namespace

Point2 Homography::apply(Point2 p) const {
    const double w = m[6] * p.x + m[7] * p.y + m[8];
    return {(m[0] * p.x + m[1] * p.y + m[2]) / w, (m[3] * p.x + m[4] * p.y + m[5]) / w};
}

Homography Homography::inverse() const {
    const auto& a = m;
    Homography r;
    r.m = {a[4] * a[8] - a[5] * a[7], a[2] * a[7] - a[1] * a[8], a[1] * a[5] - a[2] * a[4],
           a[5] * a[6] - a[3] * a[8], a[0] * a[8] - a[2] * a[6], a[2] * a[3] - a[0] * a[5],
           a[3] * a[7] - a[4] * a[6], a[1] * a[6] - a[0] * a[7], a[0] * a[4] - a[1] * a[3]};
    const double det = a[0] * r.m[0] + a[1] * r.m[3] + a[2] * r.m[6];
    for (double& v : r.m) v /= det;
    return r;
}

Result<Homography> homographyFromPoints(const std::array<Point2, 4>& from, const std::array<Point2, 4>& to) {
    if (anyThreeCollinear(from) || anyThreeCollinear(to))
        return Status::error("three of the four points are collinear");
    std::vector<double> a(64, 0.0), b(8, 0.0);
    for (int i = 0; i < 4; ++i) {
        const double x = from[i].x, y = from[i].y, u = to[i].x, v = to[i].y;
        double* r0 = &a[(2 * i) * 8];
        double* r1 = &a[(2 * i + 1) * 8];
        r0[0] = x, r0[1] = y, r0[2] = 1, r0[6] = -u * x, r0[7] = -u * y, b[2 * i] = u;
        r1[3] = x, r1[4] = y, r1[5] = 1, r1[6] = -v * x, r1[7] = -v * y, b[2 * i + 1] = v;
    }
    if (!solveLinear(a, b, 8)) return Status::error("degenerate point configuration");
    Homography h;
    for (int k = 0; k < 8; ++k) h.m[k] = b[k];
    h.m[8] = 1.0;
    return h;
}

Result<Point2> intersectLines(const Line2& l1, const Line2& l2) {
    const double d1x = l1.b.x - l1.a.x, d1y = l1.b.y - l1.a.y, d2x = l2.b.x - l2.a.x, d2y = l2.b.y - l2.a.y;
    const double den = d1x * d2y - d1y * d2x;
    const double scale = std::hypot(d1x, d1y) * std::hypot(d2x, d2y);
    if (scale == 0.0) return Status::error("a line needs two distinct points");
    if (std::fabs(den) < 1e-9 * scale) return Status::error("lines are parallel");
    const double t = ((l2.a.x - l1.a.x) * d2y - (l2.a.y - l1.a.y) * d2x) / den;
    return Point2{l1.a.x + t * d1x, l1.a.y + t * d1y};
}

Line2 vanishingLine(const Homography& ground_to_image) {
    // Lines map by the inverse transpose; the ground's line at infinity (0,0,1) becomes the third
    // row of the inverse.
    const Homography inv = ground_to_image.inverse();
    const double a = inv.m[6], b = inv.m[7], c = inv.m[8];
    if (std::fabs(b) >= std::fabs(a)) return {{0.0, -c / b}, {1000.0, -(a * 1000.0 + c) / b}};
    return {{-c / a, 0.0}, {-(b * 1000.0 + c) / a, 1000.0}};
}

Result<PerspectiveMapping> solvePerspective(const PerspectiveCanvas& c) {
    if (c.image_width <= 0 || c.image_height <= 0) return Status::error("image_width/image_height: must be > 0");
    if (!(c.camera_height_m > 0.0 && c.camera_height_m < 1e5)) return Status::error("camera_height_m: must be > 0");
    if (!(std::fabs(c.horizon.b.x - c.horizon.a.x) > 1e-6))
        return Status::error("horizon: needs two points with different x");
    struct Named {
        const char* name;
        const Line2* line;
    };
    for (Named n : {Named{"horizon", &c.horizon}, Named{"grid_left", &c.grid_left}, Named{"grid_right", &c.grid_right},
                    Named{"grid_near", &c.grid_near}, Named{"grid_far", &c.grid_far}})
        if (!finitePoint(n.line->a) || !finitePoint(n.line->b))
            return Status::error(std::string(n.name) + ": points must be finite");
    const std::pair<const Line2*, const Line2*> pairs[4] = {
        {&c.grid_left, &c.grid_near}, {&c.grid_right, &c.grid_near}, {&c.grid_right, &c.grid_far}, {&c.grid_left, &c.grid_far}};
    const char* names[4] = {"grid_left x grid_near", "grid_right x grid_near", "grid_right x grid_far",
                            "grid_left x grid_far"};
    PerspectiveMapping m;
    m.horizon = c.horizon;
    for (int i = 0; i < 4; ++i) {
        auto p = intersectLines(*pairs[i].first, *pairs[i].second);
        if (!p) return Status::error(std::string(names[i]) + ": " + p.message());
        if (p->y <= horizonV(c.horizon, p->x))
            return Status::error(std::string(names[i]) + ": grid corner lies on or above the horizon");
        m.image_quad[i] = *p;
    }
    auto h = homographyFromPoints(c.ground, m.image_quad);
    if (!h) return Status::error("ground/grid: " + h.message());
    m.ground_to_image = *h;
    m.image_to_ground = h->inverse();
    return m;
}

Result<std::vector<RidgeParams>> strokesToRidges(const PerspectiveCanvas& canvas,
                                                 const std::vector<SilhouetteStroke>& strokes) {
    auto mapping = solvePerspective(canvas);
    if (!mapping) return mapping.status();
    std::vector<RidgeParams> ridges;
    for (size_t si = 0; si < strokes.size(); ++si) {
        const SilhouetteStroke& st = strokes[si];
        const std::string where = "strokes[" + std::to_string(si) + "]";
        if (st.points.size() < 2) return Status::error(where + ".points: a stroke needs at least 2 points");
        if (!(st.width_px > 0.0 && st.width_px <= 1e4)) return Status::error(where + ".width_px: must be in (0, 10000]");
        double base = -1e300;
        for (const Point2& p : st.points) {
            if (!finitePoint(p)) return Status::error(where + ".points: must be finite");
            base = std::max(base, p.y);
        }
        if (st.base_v) base = *st.base_v;
        std::vector<Point2> ground;
        std::vector<double> elevation, arc;
        for (const Point2& p : st.points) {
            const double vh = horizonV(canvas.horizon, p.x);
            if (base <= vh) return Status::error(where + ".base_v: the stroke's foot is on or above the horizon");
            // Single-view metrology for a vertical extent standing on the ground plane.
            elevation.push_back(std::max(0.0, canvas.camera_height_m * (base - p.y) / (base - vh)));
            ground.push_back(mapping->image_to_ground.apply({p.x, base}));
            arc.push_back(arc.empty() ? 0.0
                                      : arc.back() + std::hypot(ground.back().x - ground[ground.size() - 2].x,
                                                                ground.back().y - ground[ground.size() - 2].y));
        }
        if (!(arc.back() > 1e-6)) return Status::error(where + ".points: the stroke has no horizontal extent");
        RidgeParams r;
        r.width_px = st.width_px;
        for (const Point2& g : ground) r.points.push_back({g.x, g.y});
        // The ridge profile is sampled at even arc length; resample the per-point elevations.
        const size_t n = std::max<size_t>(2, st.points.size());
        size_t j = 0;
        for (size_t k = 0; k < n; ++k) {
            const double s = arc.back() * k / (n - 1);
            while (j + 2 < arc.size() && arc[j + 1] < s) ++j;
            const double span = arc[j + 1] - arc[j];
            const double t = span > 0 ? std::clamp((s - arc[j]) / span, 0.0, 1.0) : 0.0;
            r.profile_m.push_back(elevation[j] * (1 - t) + elevation[j + 1] * t);
        }
        ridges.push_back(std::move(r));
    }
    return ridges;
}

}  // namespace terrasynth
