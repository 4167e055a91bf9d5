// Private: what several tools share: distances, the drag of a pointer, sketched strokes. Main (UI)
// thread only.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include <osg/Vec2d>

#include "editor_actions.h"
#include "terrasynth/grid.h"
#include "terrasynth/layers_tools.h"
#include "terrasynth_editor/sketch_geometry.h"

namespace terrasynth::editor::tools {

constexpr double kHandlePx = 12.0;          // how close (window pixels) the pointer must be to grab a handle
constexpr double kCourseSpacingPx = 6.0;    // level-0 pixels between kept course points
constexpr double kMinStrokeScreenPx = 6.0;  // shorter strokes are clicks
constexpr double kMovePx = 2.0;             // smaller pointer moves are not a drag step

inline double screenDistance(const osg::Vec2d& a, const osg::Vec2d& b) { return (a - b).length(); }

// The region between two level-0 picks, in the layer stack's pixels (relative to the extent).
inline Region regionBetween(std::pair<double, double> a, std::pair<double, double> b, const PixelWindow& extent,
                            RegionShape shape) {
    Region r;
    r.shape = shape;
    r.x = std::min(a.first, b.first) - extent.x;
    r.y = std::min(a.second, b.second) - extent.y;
    r.width = std::fabs(a.first - b.first);
    r.height = std::fabs(a.second - b.second);
    return r;
}

// Where a drag was pressed (window and level-0 pixels) and where it last moved by kMovePx or more.
struct DragTrack {
    osg::Vec2d press_screen, last_screen;
    std::optional<std::pair<double, double>> press_px;  // nothing when no terrain was under the press

    void start(const EditorActions& editor, const osg::Vec2d& at) {
        press_screen = last_screen = at;
        press_px = editor.pickPixel(at.x(), at.y());
    }
    bool moved(const osg::Vec2d& at) const { return screenDistance(at, last_screen) >= kMovePx; }
    // Call at the end of every drag step.
    void follow(const osg::Vec2d& at) {
        if (moved(at)) last_screen = at;
    }
};

// A stroke sketched on the terrain: the level-0 picks along the drag.
struct SketchStroke {
    DragTrack track;
    Polyline stroke_px;

    void press(const EditorActions& editor, const osg::Vec2d& at) {
        track.start(editor, at);
        stroke_px.clear();
        if (track.press_px) stroke_px.push_back(*track.press_px);
    }
    void drag(const EditorActions& editor, const osg::Vec2d& at) {
        if (!track.moved(at)) return;
        if (auto now = editor.pickPixel(at.x(), at.y())) stroke_px.push_back(*now);
        track.last_screen = at;
    }
    // Its length on the screen now (the view may have changed since it was drawn).
    double screenLength(const EditorActions& editor) const {
        double l = 0.0;
        for (size_t i = 1; i < stroke_px.size(); ++i) {
            auto a = editor.screenOfPixel(stroke_px[i - 1].first, stroke_px[i - 1].second);
            auto b = editor.screenOfPixel(stroke_px[i].first, stroke_px[i].second);
            if (a && b) l += screenDistance(*a, *b);
        }
        return l;
    }
};

}  // namespace terrasynth::editor::tools
