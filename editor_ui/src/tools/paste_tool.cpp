// paste: lasso a piece of terrain, then drag from it to where it goes; or, after a lasso on an
// exemplar's thumbnail (the exemplars panel), click where its centre goes (Gain et al. 2015 s5.3).
// A drag on a selected paste moves it. The copied piece is the editor's (EditorActions::copiedPiece).
#include <cmath>
#include <memory>
#include <optional>

#include <imgui.h>

#include "editor_actions.h"
#include "editor_tool.h"
#include "overlay.h"
#include "tool_kit.h"
#include "tool_options.h"

namespace terrasynth::editor {
namespace {
using namespace tools;

class PasteTool : public EditorTool {
public:
    explicit PasteTool(EditorActions& editor) : editor_(editor), offset_m_(editor.options().number("paste.offset", 0.0f)) {}

    const char* name() const override { return "paste"; }
    ToolGroup group() const override { return ToolGroup::Synthesis; }

    bool press(const osg::Vec2d& at, int) override {
        lasso_.press(editor_, at);
        mode_ = Mode::None;
        const auto& press_px = lasso_.track.press_px;
        if (!press_px) return false;
        const PasteItem* selected = editor_.view().findPaste(editor_.selection().paste);
        if (selected && selected->paste.exemplar < 0) {
            Polyline target = selected->paste.source;
            for (auto& q : target) q.first += selected->paste.dx, q.second += selected->paste.dy;
            if (insidePolygon(target, press_px->first, press_px->second)) {
                mode_ = Mode::MovePaste;
                return true;
            }
        }
        mode_ = editor_.copiedPiece().empty() ? Mode::Lasso : Mode::PlacePaste;
        return true;
    }

    void drag(const osg::Vec2d& at) override {
        if (mode_ == Mode::Lasso) return lasso_.drag(editor_, at);
        const auto& press_px = lasso_.track.press_px;
        if (auto now = editor_.pickPixel(at.x(), at.y()); now && press_px)
            ghost_offset_px_ = std::make_pair(now->first - press_px->first, now->second - press_px->second);
        lasso_.track.follow(at);
    }

    void release(const osg::Vec2d& at) override {
        const auto release_px = editor_.pickPixel(at.x(), at.y());
        const auto& press_px = lasso_.track.press_px;
        CopiedPiece& copied = editor_.copiedPiece();
        if (mode_ == Mode::Lasso) {
            if (lasso_.stroke_px.size() >= 3) {
                copied.outline = decimate(lasso_.stroke_px, 2.0);
                copied.exemplar = -1;
                editor_.setStatus("copied: drag the piece to where it goes (Esc to cancel)", false);
            }
        } else if (mode_ == Mode::PlacePaste && release_px && press_px) {
            double dx = release_px->first - press_px->first, dy = release_px->second - press_px->second;
            if (copied.exemplar >= 0) {
                // From an exemplar: the piece's centre lands where the pointer is released.
                const auto c = centroid(copied.outline);
                dx = std::round(release_px->first - c.first), dy = std::round(release_px->second - c.second);
            }
            if (copied.exemplar < 0 && std::hypot(dx, dy) < 1.0) editor_.setStatus("drag the copied piece to where it goes", false);
            else placePaste(std::round(dx), std::round(dy), std::nullopt);
        } else if (mode_ == Mode::MovePaste) {
            const PasteItem* p = editor_.view().findPaste(editor_.selection().paste);
            if (p && release_px && press_px) {
                const double dx = std::round(release_px->first - press_px->first);
                const double dy = std::round(release_px->second - press_px->second);
                if (dx != 0.0 || dy != 0.0) placePaste(p->paste.dx + dx, p->paste.dy + dy, p->id);
            }
        }
        abandon();
    }

    void abandon() override {
        mode_ = Mode::None;
        lasso_.stroke_px.clear();
        ghost_offset_px_.reset();
    }

    void drawOverlay(OverlayPainter& painter, bool active) override {
        using namespace overlay_colours;
        const CopiedPiece& copied = editor_.copiedPiece();
        if (!copied.empty() && copied.exemplar < 0) painter.drape(copied.outline, true, kGhost, 1.5f);
        if (ghost_offset_px_) {
            Polyline ghost;
            if (mode_ == Mode::MovePaste) {
                if (const PasteItem* p = editor_.view().findPaste(editor_.selection().paste))
                    for (const auto& q : p->paste.source)
                        ghost.push_back({q.first + p->paste.dx + ghost_offset_px_->first, q.second + p->paste.dy + ghost_offset_px_->second});
            } else if (copied.exemplar < 0) {
                for (const auto& q : copied.outline) ghost.push_back({q.first + ghost_offset_px_->first, q.second + ghost_offset_px_->second});
            }
            painter.drape(ghost, true, kPaste, 2.0f);
        }
        if (active && mode_ == Mode::Lasso) painter.drape(lasso_.stroke_px, false, kSketch, 2.0f);
    }

    void drawPanel() override {
        ImGui::TextWrapped(editor_.copiedPiece().empty()
                               ? "Lasso a piece of terrain (or of an exemplar thumbnail), then drag it where it goes."
                               : "Drag from the copied piece to where it goes. Drag a selected paste to move it. Esc cancels.");
        ImGui::DragFloat("raise (m)", &offset_m_, 5.0f, -3000.0f, 3000.0f, "%.0f");
    }

private:
    enum class Mode { None, Lasso, PlacePaste, MovePaste };

    // A new paste of the copied piece by (dx, dy), or `replacing` moved to (dx, dy).
    void placePaste(double dx, double dy, std::optional<EditId> replacing) {
        PasteConstraint paste;
        if (replacing) {
            const PasteItem* p = editor_.view().findPaste(*replacing);
            if (!p) return;
            paste = p->paste;
        } else {
            paste.source = editor_.copiedPiece().outline;
            paste.exemplar = editor_.copiedPiece().exemplar;
            paste.height_offset_m = offset_m_;
        }
        paste.dx = dx;
        paste.dy = dy;
        auto id = std::make_shared<EditId>(0);
        EditRequest r;
        r.label = replacing ? "move paste" : "paste";
        r.refresh_masks = true;
        r.run = [paste, replacing, id](EditSession& s) -> Result<PixelWindow> {
            if (!replacing) return s.addPaste(paste, id.get());
            // Moving a paste: remove and paste again, one undo step; put it back on failure.
            s.beginGesture();
            Result<PixelWindow> removed = s.removePaste(*replacing);
            Result<PixelWindow> added = removed ? s.addPaste(paste, id.get()) : removed;
            s.endGesture();
            if (!added) {
                if (removed) {
                    if (auto back = s.undo(); !back) return back.status().withContext("restoring the paste");
                }
                return added.status();
            }
            return uniteWindows(*removed, *added);
        };
        r.done = [this, id, replacing](const EditResult& res) {
            if (!res.status) return;
            editor_.selection().selectPaste(*id);
            if (!replacing) {
                // The next lasso starts a new copy.
                editor_.copiedPiece().clear();
                editor_.setStatus("pasted: drag it to move it, raise it in the inspector", false);
            }
        };
        editor_.submit(std::move(r));
    }

    EditorActions& editor_;
    float& offset_m_;  // a new paste's height offset
    Mode mode_ = Mode::None;
    SketchStroke lasso_;  // its track holds the press for every mode
    std::optional<std::pair<double, double>> ghost_offset_px_;  // the piece's offset while dragging it
};

}  // namespace

std::unique_ptr<EditorTool> makePasteTool(EditorActions& editor) { return std::make_unique<PasteTool>(editor); }

}  // namespace terrasynth::editor
