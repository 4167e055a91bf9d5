// Stack-level entry points: defaults, applyLayerStack (what `terrasynth synth` calls) and the
// printable description used by `terrasynth layers`.
#include <cstdio>
#include <sstream>

#include "layers/evaluator.h"
#include "layers/layer_json.h"
#include "terrasynth/limits.h"
#include "terrasynth/layers.h"

namespace terrasynth {

BandWeights defaultWeights(const ToolParams& tool) {
    if (std::holds_alternative<RidgeParams>(tool) || std::holds_alternative<PerspectiveParams>(tool))
        return BandWeights{1.0f, 0.0f, 0.0f};
    return BandWeights{};
}

const char* toolTypeName(const ToolParams& tool) {
    switch (tool.index()) {
        case 0: return "peak";
        case 1: return "ridge";
        case 2: return "paste";
        case 3: return "hole_fill";
        case 4: return "perspective";
        case 5: return "noise";
        default: return "group";
    }
}

Result<Heightfield> applyLayerStack(const LayerStack& stack, const Heightfield& base) {
    if (base.empty() || base.heights.size() != static_cast<size_t>(base.width) * base.height)
        return Status::error("layers: the base terrain is empty");
    if (base.width > limits::kMaxImageSide || base.height > limits::kMaxImageSide ||
        base.heights.size() > limits::kMaxImagePixels)
        return Status::error("layers: the base terrain is " + std::to_string(base.width) + "x" + std::to_string(base.height) +
                             ", more than a layer stack composes (" + std::to_string(limits::kMaxImagePixels) + " pixels)");
    if (Status s = layers::checkStackSize(stack.layers); !s) return s;
    layers::StackEvaluator evaluator(base);
    return evaluator.evaluate(stack);
}

namespace {

std::string fmt(const char* f, double a, double b = 0, double c = 0, double d = 0) {
    char buf[160];
    std::snprintf(buf, sizeof buf, f, a, b, c, d);
    return buf;
}

std::string regionText(const Region& r) {
    return std::string(r.shape == RegionShape::Rect ? "rect" : "ellipse") +
           fmt(" %.0f,%.0f %.0fx%.0f", r.x, r.y, r.width, r.height);
}

std::string toolSummary(const ToolParams& tool) {
    if (auto* p = std::get_if<PeakParams>(&tool))
        return fmt("center %.1f,%.1f height %.1f m spread %.1f px", p->center_x, p->center_y, p->height_m, p->spread_px) +
               fmt(" skew %.2f kurt %.2f", p->skewness, p->kurtosis);
    if (auto* p = std::get_if<RidgeParams>(&tool)) {
        double hi = p->profile_m.front();
        for (double v : p->profile_m) hi = std::max(hi, v);
        return fmt("%.0f points, crest up to %.1f m, width %.1f px", static_cast<double>(p->points.size()), hi, p->width_px);
    }
    if (auto* p = std::get_if<PasteParams>(&tool))
        return "from " + p->source + fmt(" at %.0f,%.0f", p->source_x, p->source_y) + " to " + regionText(p->dest) +
               (p->blend == PasteBlend::MaxGradient ? ", max-gradient" : ", replace");
    if (auto* p = std::get_if<HoleFillParams>(&tool)) {
        std::string picks;
        for (int c : p->choices) picks += (picks.empty() ? "" : ",") + std::to_string(c);
        return "hole " + regionText(p->hole) + fmt(", patch %.0f px, seed %.0f", p->patch_px, static_cast<double>(p->seed)) +
               ", picks " + picks;
    }
    if (auto* p = std::get_if<PerspectiveParams>(&tool))
        return fmt("%.0f strokes over a %.0fx%.0f canvas, camera %.1f m", static_cast<double>(p->strokes.size()),
                   p->canvas.image_width, p->canvas.image_height, p->canvas.camera_height_m);
    if (auto* p = std::get_if<NoiseParams>(&tool))
        return std::string(p->fractal.kind == FractalKind::Fbm ? "fbm" : "diamond-square") +
               fmt(" amplitude %.1f m wavelength %.0f px seed %.0f", p->fractal.amplitude_m, p->fractal.wavelength_px,
                   static_cast<double>(p->fractal.seed)) +
               (p->region ? " in " + regionText(*p->region) : "");
    const auto& g = std::get<GroupParams>(tool);
    std::string kids;
    for (const EditLayer& c : g.children) kids += (kids.empty() ? "" : ", ") + std::string(toolTypeName(c.tool));
    return "merged: " + kids;
}

std::string weightsText(const BandWeights& w) { return fmt("low %.2f mid %.2f high %.2f", w.low, w.mid, w.high); }

}  // namespace

std::string describeLayerStack(const LayerStack& stack) {
    std::ostringstream out;
    const char* sources[] = {"synthesized", "heightmap", "blank", "fractal"};
    out << "bands: high < " << stack.bands.high_mid_cut_px << " px <= mid < " << stack.bands.mid_low_cut_px
        << " px <= low\n";
    out << "  0  base         " << sources[static_cast<int>(stack.base.source)];
    if (stack.base.source == BaseSource::Heightmap) out << " " << stack.base.path;
    if (stack.base.source == BaseSource::Blank) out << fmt(" %.1f m", stack.base.height_m);
    if (stack.base.source == BaseSource::Fractal)
        out << (stack.base.fractal.kind == FractalKind::Fbm ? " fbm" : " diamond-square")
            << fmt(" seed %.0f amplitude %.1f m", static_cast<double>(stack.base.fractal.seed), stack.base.fractal.amplitude_m);
    out << "  [" << weightsText(stack.base.weights) << "]\n";
    for (size_t i = 0; i < stack.layers.size(); ++i) {
        const EditLayer& l = stack.layers[i];
        char head[96];
        std::snprintf(head, sizeof head, "%3zu  %-12s %s%s", i + 1, toolTypeName(l.tool), l.visible ? "" : "(hidden) ",
                      l.name.empty() ? "" : ("\"" + l.name + "\"").c_str());
        out << head << "  [" << weightsText(l.weights) << "]  " << toolSummary(l.tool) << "\n";
    }
    return out.str();
}

}  // namespace terrasynth
