// Private: what is selected in the editor, and what Del removes. Main (UI) thread only.
//
// At most one of a point, a curve (with one of its widgets, or none) and a paste is selected; a layer
// of the stack is selected on its own (the layers panel). Ids are the session's (EditId); a selected
// id that the session no longer has selects nothing.
#pragma once

#include <optional>

#include "terrasynth_editor/edit_worker.h"
#include "terrasynth_editor/sketch_geometry.h"

namespace terrasynth::editor {

struct Selection {
    EditId point = 0, curve = 0, paste = 0;
    int widget = -1;  // index into the selected curve's widgets, -1 for none
    int layer = -1;   // index into the layer stack, -1 for none

    // Each selects its item and deselects the other two kinds (a curve also drops its widget).
    void selectPoint(EditId id);
    void selectCurve(EditId id);
    void selectPaste(EditId id);
    // Points, curves, widgets and pastes (Esc); the layer stays.
    void clearItems();
    // The request that removes what Del acts on: the point, else the curve's selected widget, else the
    // curve, else the paste; that part of the selection is cleared. Nothing when nothing is selected.
    std::optional<EditRequest> takeDeletion();
};

// A piece of terrain copied for pasting (Gain et al. 2015 s5.3): a lasso on the terrain (exemplar
// -1, level-0 pixels) or on an exemplar's thumbnail (that exemplar's pixels).
struct CopiedPiece {
    Polyline outline;
    int exemplar = -1;

    bool empty() const { return outline.empty(); }
    void clear() { *this = CopiedPiece{}; }
};

}  // namespace terrasynth::editor
