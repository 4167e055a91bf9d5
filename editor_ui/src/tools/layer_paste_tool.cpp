// layerpaste: drag a rectangle to copy it, then click where the copy goes: a paste layer from the
// terrain below (Bradbury et al. 2014 s4.3), landing as the rectangle's inscribed ellipse centred
// on the click.
#include <memory>
#include <optional>

#include <imgui.h>

#include "editor_actions.h"
#include "editor_tool.h"
#include "overlay.h"
#include "tool_kit.h"

namespace terrasynth::editor {
namespace {
using namespace tools;

class LayerPasteTool : public EditorTool {
public:
    explicit LayerPasteTool(EditorActions& editor) : editor_(editor) {}

    const char* name() const override { return "layerpaste"; }
    ToolGroup group() const override { return ToolGroup::Layers; }

    bool press(const osg::Vec2d& at, int) override {
        region_.press(editor_, at);
        return true;
    }
    void drag(const osg::Vec2d& at) override { region_.drag(at); }

    void release(const osg::Vec2d&) override {
        region_.active = false;
        const PixelWindow& e = editor_.view().extent;
        const auto& press_px = region_.track.press_px;
        if (const auto end = region_.end(editor_)) {
            source_ = regionBetween(*press_px, *end, e, RegionShape::Rect);
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

    void abandon() override { region_.active = false; }
    void escape() override { source_.reset(); }

    void drawOverlay(OverlayPainter& painter, bool active) override {
        if (source_) {
            const PixelWindow& e = editor_.view().extent;
            const Region& r = *source_;
            const double x0 = r.x + e.x, y0 = r.y + e.y;
            painter.drape({{x0, y0}, {x0 + r.width, y0}, {x0 + r.width, y0 + r.height}, {x0, y0 + r.height}}, true,
                          overlay_colours::kGhost, 1.5f);
        }
        if (active) region_.draw(editor_, painter);
    }

    void drawPanel() override { ImGui::TextWrapped(source_ ? "Click where the copy goes." : "Drag a rectangle to copy (s4.3)."); }

private:
    EditorActions& editor_;
    RegionDrag region_;
    std::optional<Region> source_;  // the copied rectangle, in the stack's pixels
};

}  // namespace

std::unique_ptr<EditorTool> makeLayerPasteTool(EditorActions& editor) { return std::make_unique<LayerPasteTool>(editor); }

}  // namespace terrasynth::editor
