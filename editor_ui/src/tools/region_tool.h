// Private: a tool that drags a rectangle (or its inscribed ellipse) from the press to the pointer
// and acts on the release (the layer paste, hole fill and noise tools).
#pragma once

#include <optional>
#include <utility>

#include "editor_tool.h"
#include "overlay.h"
#include "tool_kit.h"

namespace terrasynth::editor::tools {

class RegionTool : public EditorTool {
public:
    explicit RegionTool(EditorActions& editor) : editor_(editor) {}

    bool press(const osg::Vec2d& at, int) override {
        track_.start(editor_, at);
        dragging_ = true;
        return true;
    }
    void drag(const osg::Vec2d& at) override { track_.follow(at); }
    void release(const osg::Vec2d&) override {
        dragging_ = false;
        finish();
    }
    void abandon() override { dragging_ = false; }
    // The rectangle from the press to the pointer, on the terrain, while dragging.
    void drawOverlay(OverlayPainter& painter, bool active) override {
        if (!active || !dragging_ || !track_.press_px) return;
        if (const auto now = editor_.pickPixel(track_.last_screen.x(), track_.last_screen.y())) {
            const double x0 = track_.press_px->first, y0 = track_.press_px->second, x1 = now->first, y1 = now->second;
            painter.drape({{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}, true, overlay_colours::kSketch, 1.5f);
        }
    }

protected:
    // The drag is over: the press is in track_, the region ends at end().
    virtual void finish() = 0;
    // Where the region ends on the terrain; nothing for a click (or nothing under the pointer).
    std::optional<std::pair<double, double>> end() const {
        const auto at = editor_.pickPixel(track_.last_screen.x(), track_.last_screen.y());
        if (!at || !track_.press_px || screenDistance(track_.last_screen, track_.press_screen) < kMinStrokeScreenPx)
            return std::nullopt;
        return at;
    }

    EditorActions& editor_;
    DragTrack track_;

private:
    bool dragging_ = false;
};

}  // namespace terrasynth::editor::tools
