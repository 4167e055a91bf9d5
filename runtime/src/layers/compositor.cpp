#include "layers/compositor.h"

#include <algorithm>
#include <cmath>

#include "layers/parallel.h"

namespace terrasynth::layers {
namespace {

Band bandOf(const BandSplit& split, int level, int depth) {
    return level == depth ? Band::Low : split.bandOfLevel(level);
}

// Combines one row of one level: the base row scaled by its weight, then every layer in order.
void combineRow(const CompositionPlan& plan, int level, int y, float* acc) {
    const int depth = plan.base->depth();
    const Band band = bandOf(plan.split, level, depth);
    const Plane& base = plan.base->levels[level];
    const float wb = plan.base_weights.get(band);
    const float* b = base.row(y);
    const int w = base.width;
    if (wb == 1.0f) {
        std::copy(b, b + w, acc);
    } else {
        for (int x = 0; x < w; ++x) acc[x] = wb * b[x];
    }
    const bool residual = level == depth;
    for (const PlannedOp& op : plan.ops) {
        const LayerContent& c = *op.content;
        const float wt = op.weights.get(band);
        const Box& box = c.support[level];
        if (wt == 0.0f || y < box.y0 || y >= box.y1) continue;
        const float* cr = c.coeffs.levels[level].row(y);
        const int x0 = box.x0, x1 = box.x1;
        if (c.kind == OpKind::Add) {
            for (int x = x0; x < x1; ++x) acc[x] += wt * cr[x];
            continue;
        }
        const float* mr = c.mask.levels[level].row(y);
        if (c.kind == OpKind::Replace || residual) {
            for (int x = x0; x < x1; ++x) acc[x] += wt * mr[x] * (cr[x] - acc[x]);
        } else {
            // s4.3: keep the steeper of source and destination, coefficient by coefficient.
            for (int x = x0; x < x1; ++x) {
                const float s = std::fabs(cr[x]) > std::fabs(acc[x]) ? cr[x] : acc[x];
                acc[x] += wt * mr[x] * (s - acc[x]);
            }
        }
    }
}

}  // namespace

size_t LayerContent::bytes() const {
    size_t n = 0;
    for (const Plane& p : coeffs.levels) n += p.samples.size() * sizeof(float);
    for (const Plane& p : mask.levels) n += p.samples.size() * sizeof(float);
    return n;
}

void computeSupport(LayerContent& content) {
    const Pyramid& src = content.kind == OpKind::Add ? content.coeffs : content.mask;
    content.support.clear();
    for (const Plane& p : src.levels) content.support.push_back(nonZeroBox(p));
}

void Compositor::compose(const CompositionPlan& plan, Plane& out) {
    const int depth = plan.base->depth();
    levels_.resize(depth + 1);
    for (int i = depth; i >= 0; --i) {
        const Plane& shape = plan.base->levels[i];
        Plane& target = i == 0 ? out : levels_[i];
        if (target.width != shape.width || target.height != shape.height) target = Plane(shape.width, shape.height);
        const int w = shape.width;
        const long cost = static_cast<long>(w) * (4 + static_cast<long>(plan.ops.size()));
        parallelFor(shape.height, cost, [&](int y0, int y1) {
            for (int y = y0; y < y1; ++y) combineRow(plan, i, y, target.row(y));
            if (i < depth) expandRows(levels_[i + 1], w, shape.height, y0, y1, target.row(y0), /*accumulate=*/true);
        });
    }
}

Pyramid Compositor::combine(const CompositionPlan& plan) {
    Pyramid out;
    out.levels.resize(plan.base->levels.size());
    for (size_t i = 0; i < out.levels.size(); ++i) {
        const Plane& shape = plan.base->levels[i];
        out.levels[i] = Plane(shape.width, shape.height);
        Plane& target = out.levels[i];
        parallelFor(shape.height, static_cast<long>(shape.width) * (2 + plan.ops.size()), [&](int y0, int y1) {
            for (int y = y0; y < y1; ++y) combineRow(plan, static_cast<int>(i), y, target.row(y));
        });
    }
    return out;
}

}  // namespace terrasynth::layers
