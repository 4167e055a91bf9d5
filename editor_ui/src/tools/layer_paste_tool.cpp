// layerpaste: drag a rectangle to copy it, then click where the copy goes: a paste layer from the
// terrain below (Bradbury et al. 2014 s4.3), landing as the rectangle's inscribed ellipse centred
// on the click.
#include <memory>
#include <optional>

#include <imgui.h>

#include "editor_actions.h"
#include "region_tool.h"

namespace terrasynth::editor {
namespace {
using namespace tools;

class LayerPasteTool : public RegionTool {
public:
    using RegionTool::RegionTool;

    const char* name() const override { return "layerpaste"; }
    ToolGroup group() const override { return ToolGroup::Layers; }

    void escape() override { source_.reset(); }

    void drawOverlay(OverlayPainter& painter, bool active) override {
        if (source_) {
            const PixelWindow& e = editor_.view().extent;
            const Region& r = *source_;
            const double x0 = r.x + e.x, y0 = r.y + e.y;
            painter.drape({{x0, y0}, {x0 + r.width, y0}, {x0 + r.width, y0 + r.height}, {x0, y0 + r.height}}, true,
                          overlay_colours::kGhost, 1.5f);
        }
        RegionTool::drawOverlay(painter, active);
    }

    void drawPanel() override { ImGui::TextWrapped(source_ ? "Click where the copy goes." : "Drag a rectangle to copy (s4.3)."); }

private:
    void finish() override {
        const PixelWindow& e = editor_.view().extent;
        const auto& press_px = track_.press_px;
        if (const auto to = end()) {
            source_ = regionBetween(*press_px, *to, e, RegionShape::Rect);
            editor_.setStatus("copied: click where the copy goes", false);
            return;
        }
        if (!source_ || !press_px) return;
        // The second step: the copied rectangle lands centred on the click.
        PasteParams paste;
        paste.source_x = source_->x;
        paste.source_y = source_->y;
        paste.dest = *source_;
        paste.dest.shape = RegionShape::Ellipse;
        paste.dest.x = press_px->first - e.x - 0.5 * paste.dest.width;
        paste.dest.y = press_px->second - e.y - 0.5 * paste.dest.height;
        paste.feather_px = 8.0;
        source_.reset();
        editor_.addLayer("layer paste", paste);
    }

    std::optional<Region> source_;  // the copied rectangle, in the stack's pixels
};

}  // namespace

std::unique_ptr<EditorTool> makeLayerPasteTool(EditorActions& editor) { return std::make_unique<LayerPasteTool>(editor); }

}  // namespace terrasynth::editor
