#include "selection.h"

namespace terrasynth::editor {

void Selection::selectPoint(EditId id) {
    point = id;
    curve = paste = 0;
}

void Selection::selectCurve(EditId id) {
    curve = id;
    point = paste = 0;
    widget = -1;
}

void Selection::selectPaste(EditId id) {
    paste = id;
    point = curve = 0;
}

void Selection::clearItems() {
    point = curve = paste = 0;
    widget = -1;
}

std::optional<EditRequest> Selection::takeDeletion() {
    EditRequest r;
    if (point) {
        const EditId id = point;
        r.label = "remove point";
        r.run = [id](EditSession& s) { return s.removePoint(id); };
        point = 0;
    } else if (curve && widget >= 0) {
        const EditId id = curve;
        const int index = widget;
        r.label = "remove widget";
        r.run = [id, index](EditSession& s) { return s.removeWidget(id, index); };
        widget = -1;
    } else if (curve) {
        const EditId id = curve;
        r.label = "remove curve";
        r.run = [id](EditSession& s) { return s.removeCurve(id); };
        curve = 0;
    } else if (paste) {
        const EditId id = paste;
        r.label = "remove paste";
        r.refresh_masks = true;
        r.run = [id](EditSession& s) { return s.removePaste(id); };
        paste = 0;
    } else {
        return std::nullopt;
    }
    return r;
}

}  // namespace terrasynth::editor
