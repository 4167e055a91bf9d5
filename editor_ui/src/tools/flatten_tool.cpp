// flatten: click to flatten a disc of terrain, a layer that pulls the heights under the brush toward
// their mean there (Bradbury et al. 2014 s4.3's paste layer, from the terrain below onto itself:
// "replace" blending, the source's relief scaled by 1 - strength about the mean under the mask,
// match_height). The pull fades to nothing over the outer `falloff` of the radius (the mask's
// feather), and the layer's band sliders weaken it per band afterwards.
#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>

#include <imgui.h>

#include "editor_actions.h"
#include "editor_tool.h"
#include "overlay.h"
#include "tool_options.h"

namespace terrasynth::editor {
namespace {

constexpr float kMaxStrength = 0.99f;  // a paste's vertical scale must stay > 0

class FlattenTool : public EditorTool {
public:
    explicit FlattenTool(EditorActions& editor)
        : editor_(editor),
          radius_px_(editor.options().number("flatten.radius", 32.0f)),
          strength_(editor.options().number("flatten.strength", 0.9f)),
          falloff_(editor.options().number("flatten.falloff", 0.5f)) {}

    const char* name() const override { return "flatten"; }
    ToolGroup group() const override { return ToolGroup::Layers; }

    bool press(const osg::Vec2d& at, int) override {
        const auto px = editor_.pickPixel(at.x(), at.y());
        if (!px) return false;
        const PixelWindow& e = editor_.view().extent;
        const double r = std::max(1.0f, radius_px_);
        PasteParams flatten;  // source "terrain": the layers below
        flatten.dest.shape = RegionShape::Ellipse;
        flatten.dest.x = std::round(px->first - e.x - r);
        flatten.dest.y = std::round(px->second - e.y - r);
        flatten.dest.width = flatten.dest.height = std::round(2.0 * r);
        if (flatten.dest.x < 0 || flatten.dest.y < 0 || flatten.dest.x + flatten.dest.width > e.width ||
            flatten.dest.y + flatten.dest.height > e.height) {
            editor_.setStatus("flatten: the brush must lie inside the extent", true);
            return false;
        }
        flatten.source_x = flatten.dest.x;
        flatten.source_y = flatten.dest.y;
        flatten.blend = PasteBlend::Replace;
        flatten.match_height = true;
        flatten.vertical_scale = 1.0 - std::clamp(strength_, 0.0f, kMaxStrength);
        flatten.feather_px = std::clamp(falloff_, 0.0f, 1.0f) * r;
        editor_.addLayer("flatten", flatten);
        return false;
    }

    void hover(const osg::Vec2d& at) override { hover_px_ = editor_.pickPixel(at.x(), at.y()); }

    void drawOverlay(OverlayPainter& painter, bool active) override {
        if (!active || !hover_px_) return;
        painter.circle(hover_px_->first, hover_px_->second, radius_px_, overlay_colours::kSketch, 1.5f);
        const float inner = radius_px_ * (1.0f - std::clamp(falloff_, 0.0f, 1.0f));
        if (inner > 1.0f) painter.circle(hover_px_->first, hover_px_->second, inner, overlay_colours::kGhost, 1.0f);
    }

    void drawPanel() override {
        ImGui::TextWrapped("Click to flatten the terrain under the brush toward its mean height there.");
        ImGui::DragFloat("radius (px)", &radius_px_, 0.5f, 2.0f, 400.0f, "%.0f");
        ImGui::SliderFloat("strength", &strength_, 0.0f, kMaxStrength, "%.2f");
        ImGui::SliderFloat("falloff", &falloff_, 0.0f, 1.0f, "%.2f");
    }

private:
    EditorActions& editor_;
    float& radius_px_;
    float& strength_;  // 0: no change, 0.99: flat but for 1% of the relief
    float& falloff_;   // the outer part of the radius over which the pull fades, 0..1
    std::optional<std::pair<double, double>> hover_px_;
};

}  // namespace

std::unique_ptr<EditorTool> makeFlattenTool(EditorActions& editor) { return std::make_unique<FlattenTool>(editor); }

}  // namespace terrasynth::editor
