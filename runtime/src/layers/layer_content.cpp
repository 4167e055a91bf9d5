#include "layers/layer_content.h"

#include <algorithm>
#include <cmath>

#include "core/paths.h"
#include "terrasynth/heightfield_io.h"
#include "terrasynth/limits.h"

namespace terrasynth::layers {
namespace {

// Bilinear resize with pixel centres aligned, for imported base heightmaps.
Heightfield resizeTo(const Heightfield& in, int w, int h, const Heightfield& like) {
    Heightfield out(w, h, like.meters_per_pixel_x);
    out.meters_per_pixel_y = like.meters_per_pixel_y;
    for (int y = 0; y < h; ++y) {
        const double sy = std::clamp((y + 0.5) * in.height / h - 0.5, 0.0, in.height - 1.0);
        const int y0 = static_cast<int>(sy), y1 = std::min(y0 + 1, in.height - 1);
        const double ty = sy - y0;
        for (int x = 0; x < w; ++x) {
            const double sx = std::clamp((x + 0.5) * in.width / w - 0.5, 0.0, in.width - 1.0);
            const int x0 = static_cast<int>(sx), x1 = std::min(x0 + 1, in.width - 1);
            const double tx = sx - x0;
            const double top = in.at(x0, y0) * (1 - tx) + in.at(x1, y0) * tx;
            const double bot = in.at(x0, y1) * (1 - tx) + in.at(x1, y1) * tx;
            out.at(x, y) = static_cast<float>(top * (1 - ty) + bot * ty);
        }
    }
    return out;
}

}  // namespace

bool readsBelow(const ToolParams& tool) {
    return std::holds_alternative<PasteParams>(tool) || std::holds_alternative<HoleFillParams>(tool) ||
           std::holds_alternative<GroupParams>(tool);
}

// A ridge ridgeRelief can take, at a cost bounded by limits::kMaxRidgeCost on this grid.
static Status checkRidge(const RidgeParams& ridge, int w, int h) {
    if (Status s = validateRidge(ridge); !s) return s;
    const uint64_t cost = ridgeReliefCost(ridge, w, h);
    if (cost > limits::kMaxRidgeCost)
        return Status::error("points: the ridge would visit " + std::to_string(cost) + " pixels of the grid, at most " +
                             std::to_string(limits::kMaxRidgeCost) + " (fewer points or a narrower width_px)");
    return Status::ok();
}

Result<Heightfield> toolRelief(const ToolParams& tool, const Heightfield& grid) {
    const int w = grid.width, h = grid.height;
    const double mpp = grid.meters_per_pixel_x;
    Heightfield relief;
    if (auto* peak = std::get_if<PeakParams>(&tool)) {
        auto r = peakRelief(*peak, w, h, mpp);
        if (!r) return r.status();
        relief = std::move(*r);
    } else if (auto* ridge = std::get_if<RidgeParams>(&tool)) {
        if (Status s = checkRidge(*ridge, w, h); !s) return s;
        relief = ridgeRelief(*ridge, w, h, mpp);
    } else if (auto* noise = std::get_if<NoiseParams>(&tool)) {
        if (Status s = validateFractal(noise->fractal); !s) return s;
        relief = fractalHeightfield(noise->fractal, w, h, mpp);
        if (noise->region) {
            const std::vector<float> m = regionMask(*noise->region, noise->feather_px, w, h);
            for (size_t i = 0; i < m.size(); ++i) relief.heights[i] *= m[i];
        }
    } else if (auto* persp = std::get_if<PerspectiveParams>(&tool)) {
        auto ridges = strokesToRidges(persp->canvas, persp->strokes);
        if (!ridges) return ridges.status();
        relief = Heightfield(w, h, mpp);
        for (size_t k = 0; k < ridges->size(); ++k)
            if (Status s = checkRidge((*ridges)[k], w, h); !s) return s.withContext("strokes[" + std::to_string(k) + "]");
        for (const RidgeParams& r : *ridges) {
            const Heightfield one = ridgeRelief(r, w, h, mpp);
            for (size_t i = 0; i < one.heights.size(); ++i)
                if (std::fabs(one.heights[i]) > std::fabs(relief.heights[i])) relief.heights[i] = one.heights[i];
        }
    } else {
        TERRASYNTH_REQUIRE(false, "toolRelief called for a layer that reads the terrain below");
    }
    relief.meters_per_pixel_y = grid.meters_per_pixel_y;
    return relief;
}

std::shared_ptr<LayerContent> additiveContent(const Heightfield& relief, const BandSplit& split) {
    auto c = std::make_shared<LayerContent>();
    c->kind = OpKind::Add;
    c->coeffs = buildLaplacian(toPlane(relief), split.depth());
    computeSupport(*c);
    return c;
}

std::shared_ptr<LayerContent> blendedContent(const Heightfield& content, const std::vector<float>& mask, OpKind kind,
                                             const BandSplit& split) {
    auto c = std::make_shared<LayerContent>();
    c->kind = kind;
    c->coeffs = buildLaplacian(toPlane(content), split.depth());
    Plane m(content.width, content.height);
    m.samples = mask;
    c->mask = buildGaussian(m, split.depth());
    computeSupport(*c);
    return c;
}

Result<std::shared_ptr<LayerContent>> pasteContent(const PasteParams& p, const Heightfield& below, const BandSplit& split,
                                                   const std::string& base_dir) {
    const int w = below.width, h = below.height;
    Heightfield source;
    if (p.source == "terrain") {
        source = below;
    } else {
        auto ex = readExemplar(detail::resolveRelative(base_dir, p.source));
        if (!ex) return Status::error("source: " + ex.message());
        // Keep real-world feature sizes: bring the DEM to the terrain's spacing first.
        source = resampleToSpacing(ex->field, below.meters_per_pixel_x);
    }
    const int rx = static_cast<int>(std::lround(p.dest.x)), ry = static_cast<int>(std::lround(p.dest.y));
    const int rw = static_cast<int>(std::lround(p.dest.width)), rh = static_cast<int>(std::lround(p.dest.height));
    const int sx = static_cast<int>(std::lround(p.source_x)), sy = static_cast<int>(std::lround(p.source_y));
    if (sx < 0 || sy < 0 || sx + rw > source.width || sy + rh > source.height)
        return Status::error("source_x/source_y: the " + std::to_string(rw) + "x" + std::to_string(rh) +
                             " source rectangle at (" + std::to_string(sx) + ", " + std::to_string(sy) +
                             ") does not fit in the source (" + std::to_string(source.width) + "x" +
                             std::to_string(source.height) + " px at the terrain spacing)");
    const std::vector<float> mask = regionMask(p.dest, p.feather_px, w, h);
    double mask_sum = 0, src_mean = 0, dst_mean = 0;
    for (int y = std::max(0, ry); y < std::min(h, ry + rh); ++y)
        for (int x = std::max(0, rx); x < std::min(w, rx + rw); ++x) {
            const double m = mask[static_cast<size_t>(y) * w + x];
            mask_sum += m;
            src_mean += m * source.at(sx + x - rx, sy + y - ry);
            dst_mean += m * below.at(x, y);
        }
    if (mask_sum <= 0) return Status::error("dest: the paste region covers no pixel of the terrain");
    src_mean /= mask_sum;
    dst_mean /= mask_sum;
    const double target_mean = p.match_height ? dst_mean : src_mean;
    // Content = the source over the region plus a margin (so pyramid coefficients near the mask edge
    // are the source's own, as multi-band blending needs), the terrain below elsewhere.
    const int margin = 1 << split.depth();
    Heightfield content = below;
    for (int y = std::max(0, ry - margin); y < std::min(h, ry + rh + margin); ++y)
        for (int x = std::max(0, rx - margin); x < std::min(w, rx + rw + margin); ++x) {
            const int qx = sx + x - rx, qy = sy + y - ry;
            if (qx < 0 || qy < 0 || qx >= source.width || qy >= source.height) continue;
            content.at(x, y) = static_cast<float>(target_mean + p.vertical_scale * (source.at(qx, qy) - src_mean));
        }
    return blendedContent(content, mask, p.blend == PasteBlend::MaxGradient ? OpKind::MaxGradient : OpKind::Replace,
                          split);
}

Result<std::shared_ptr<LayerContent>> holeFillContent(const HoleFillParams& p, const Heightfield& below,
                                                      const BandSplit& split) {
    auto filled = holeFill(below, p);
    if (!filled) return filled.status();
    // The quilted fill already meets the terrain without a step (its rim mismatch is relaxed away), so
    // it acts as the change it makes: zero outside the hole, and with unit weights the hole holds
    // exactly the chosen variant. A mask blend would let the coarse bands of a small hole keep part
    // of the old terrain.
    Heightfield delta = *filled;
    for (size_t i = 0; i < delta.heights.size(); ++i) delta.heights[i] -= below.heights[i];
    return additiveContent(delta, split);
}

Result<Heightfield> baseHeights(const BaseLayer& base, const Heightfield& synthesized, const std::string& base_dir) {
    const int w = synthesized.width, h = synthesized.height;
    switch (base.source) {
        case BaseSource::Synthesized:
            return synthesized;
        case BaseSource::Blank: {
            Heightfield f(w, h, synthesized.meters_per_pixel_x, static_cast<float>(base.height_m));
            f.meters_per_pixel_y = synthesized.meters_per_pixel_y;
            return f;
        }
        case BaseSource::Fractal: {
            if (Status s = validateFractal(base.fractal); !s) return s;
            Heightfield f = fractalHeightfield(base.fractal, w, h, synthesized.meters_per_pixel_x);
            f.meters_per_pixel_y = synthesized.meters_per_pixel_y;
            return f;
        }
        case BaseSource::Heightmap: {
            auto ex = readExemplar(detail::resolveRelative(base_dir, base.path));
            if (!ex) return Status::error("path: " + ex.message());
            return resizeTo(ex->field, w, h, synthesized);
        }
    }
    return Status::error("source: unknown base source");
}

}  // namespace terrasynth::layers

namespace terrasynth {

Result<Heightfield> readBaseHeightmap(const LayerStack& stack) {
    if (stack.base.source != BaseSource::Heightmap) return Status::error("layers[0]: the base is not a heightmap");
    auto exemplar = readExemplar(detail::resolveRelative(stack.base_dir, stack.base.path));
    if (!exemplar) return exemplar.status().withContext("layers[0].path");
    return std::move(exemplar->field);
}

}  // namespace terrasynth
