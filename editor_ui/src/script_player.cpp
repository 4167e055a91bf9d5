#include "script_player.h"

#include <cstdio>

#include "terrasynth/heightfield_io.h"
#include "tool_options.h"

namespace terrasynth::editor {
namespace {

int buttonOf(const ScriptCommand& c) {
    if (c.args.empty() || c.args[0] == "left") return 0;
    return c.args[0] == "right" ? 1 : 2;
}

}  // namespace

ScriptPlayer::ScriptPlayer(std::vector<ScriptCommand> script, std::string path, EditorActions& editor, EditorProbe& probe,
                           host::HostWindow& host)
    : script_(std::move(script)), path_(std::move(path)), editor_(editor), probe_(probe), host_(host) {}

void ScriptPlayer::fail(const ScriptCommand& c, const std::string& why) {
    std::fprintf(stderr, "terrasynth_editor: %s:%d: %s: %s\n", path_.c_str(), c.line, c.op.c_str(), why.c_str());
    failed_ = done_ = true;
}

void ScriptPlayer::step() {
    if (!probe_.ready()) return;
    while (pc_ < script_.size() && !done_) {
        yield_ = false;
        const bool finished = run(script_[pc_]);
        if (finished) {
            ++pc_;
            wait_ = Wait{};
        }
        // Injected input reaches the editor at the next beginFrame: one input step per frame.
        if (!finished || yield_) return;
    }
    if (pc_ >= script_.size()) done_ = true;
}

bool ScriptPlayer::run(const ScriptCommand& c) {
    const double now = steadySeconds();
    const bool first = !wait_.started;
    wait_.started = true;
    const auto& n = c.numbers;
    if (c.op == "wait") {
        if (first) wait_.frames = static_cast<int>(n[0]);
        return wait_.frames-- <= 0;
    }
    if (c.op == "sleep") {
        if (first) wait_.until_s = now + n[0] / 1000.0;
        return now >= wait_.until_s;
    }
    if (c.op == "settle") {
        if (first) wait_.deadline_s = now + (n.empty() ? 120.0 : n[0]);
        wait_.settle_frames = probe_.settled() ? wait_.settle_frames + 1 : 0;
        if (wait_.settle_frames >= 3) return true;
        if (now > wait_.deadline_s) fail(c, "the editor did not settle in time");
        return false;
    }
    if (c.op == "view") {
        const GridFrame& f = editor_.view().frame;
        const osg::Vec3d centre(f.worldX(n[0]), f.worldY(n[1]), editor_.groundAtPixel(n[0], n[1]));
        if (c.args[0] == "aerial") editor_.viewAerial(centre, n[2]);
        else editor_.viewFree(centre, n[2], n[3], n[4]);
        return true;
    }
    if (c.op == "tool") {
        if (!editor_.selectTool(c.args[0])) fail(c, "unknown tool '" + c.args[0] + "'");
        return true;
    }
    if (c.op == "set") {
        if (Status s = editor_.options().set(c.args[0], c.args[1]); !s) fail(c, s.message());
        return true;
    }
    if (c.op == "move") {
        host_.injectMouseMove(n[0], n[1]);
        yield_ = true;
        return true;
    }
    if (c.op == "press" || c.op == "release") {
        host_.injectMouseButton(buttonOf(c), c.op == "press");
        yield_ = true;
        return true;
    }
    if (c.op == "click") {
        // Press this frame, release the next.
        if (first) {
            host_.injectMouseButton(buttonOf(c), true);
            return false;
        }
        host_.injectMouseButton(buttonOf(c), false);
        yield_ = true;
        return true;
    }
    if (c.op == "drag" || c.op == "drag-item") {
        // drag: from (X0, Y0) to (X1, Y1); drag-item: from the item's centre, found once when the drag
        // starts (it may move with what it edits), by (DX, DY).
        const bool item = c.op == "drag-item";
        const int steps = n.size() > (item ? 2u : 4u) ? static_cast<int>(n[item ? 2 : 4]) : 10;
        if (first) {
            if (item) {
                const auto r = probe_.itemRect(c.args[0]);
                if (!r) {
                    fail(c, "no item '" + c.args[0] + "' on screen");
                    return true;
                }
                wait_.drag_from = osg::Vec2d(0.5 * (r->x + r->z), 0.5 * (r->y + r->w));
            } else {
                wait_.drag_from = osg::Vec2d(n[0], n[1]);
            }
            wait_.drag_step = -1;
        }
        const double x0 = wait_.drag_from.x(), y0 = wait_.drag_from.y();
        const int s = wait_.drag_step++;
        if (s == -1) host_.injectMouseMove(x0, y0);
        else if (s == 0) host_.injectMouseButton(0, true);
        else if (s <= steps && item) host_.injectMouseMove(x0 + n[0] * s / steps, y0 + n[1] * s / steps);
        else if (s <= steps) {
            const double f = static_cast<double>(s) / steps;
            host_.injectMouseMove(n[0] + f * (n[2] - n[0]), n[1] + f * (n[3] - n[1]));
        } else {
            host_.injectMouseButton(0, false);
            yield_ = true;
            return true;
        }
        return false;
    }
    if (c.op == "item") {
        const auto r = probe_.itemRect(c.args[0]);
        if (!r) {
            fail(c, "no panel item '" + c.args[0] + "' on screen");
            return true;
        }
        const double dx = n.size() > 1 ? n[0] : 0.0, dy = n.size() > 1 ? n[1] : 0.0;
        host_.injectMouseMove(0.5 * (r->x + r->z) + dx, 0.5 * (r->y + r->w) + dy);
        yield_ = true;
        return true;
    }
    if (c.op == "key") {
        int key = 0, mods = 0;
        parseKeySpec(c.args[0], &key, &mods);
        if (first) {
            host_.injectKey(key, true, mods);
            return false;
        }
        host_.injectKey(key, false, mods);
        yield_ = true;
        return true;
    }
    if (c.op == "scroll") {
        host_.injectScroll(0.0, n[0]);
        yield_ = true;
        return true;
    }
    if (c.op == "screenshot") {
        if (first) {
            host_.requestScreenshot(c.args[0], c.args.size() < 2 || c.args[1] == "ui");
            return false;
        }
        if (!host_.lastScreenshotStatus()) fail(c, host_.lastScreenshotStatus().message());
        return true;
    }
    if (c.op == "save" || c.op == "heights") {
        if (first) {
            wait_.errors_before = probe_.errorsSinceCheck();  // a new error is this command's
            if (c.op == "save") {
                editor_.save(c.args.empty() ? editor_.savePath() : c.args[0]);
            } else {
                EditRequest r;
                r.label = "write heights " + c.args[0];
                r.run = [path = c.args[0]](EditSession& s) -> Result<PixelWindow> {
                    if (Status st = writeHeightfieldF32(path, s.heights()); !st) return st;
                    return PixelWindow{};
                };
                editor_.submit(std::move(r));
            }
            return false;
        }
        if (!probe_.idle()) return false;
        probe_.collectResults();
        if (probe_.errorsSinceCheck() > wait_.errors_before) fail(c, probe_.lastError());
        return true;
    }
    if (c.op == "undo-all") {
        if (first) wait_.deadline_s = now + 300.0;
        if (!probe_.idle()) return false;
        probe_.collectResults();
        if (!editor_.view().can_undo) return true;
        if (now > wait_.deadline_s) {
            fail(c, "still undoing after 300 s");
            return true;
        }
        editor_.undo();
        return false;
    }
    if (c.op == "wait-autosave") {
        if (first) wait_.deadline_s = now + 60.0;
        if (probe_.autosaveHoldsTheLastEdit()) return true;
        if (now > wait_.deadline_s) fail(c, "no autosave of the current edit within 60 s");
        return false;
    }
    if (c.op == "expect-error" || c.op == "expect-ok") {
        if (!probe_.idle()) return false;
        probe_.collectResults();
        const int errors = probe_.errorsSinceCheck();
        if (c.op == "expect-ok" && errors > 0) fail(c, "an edit failed: " + probe_.lastError());
        if (c.op == "expect-error" && (errors == 0 || probe_.lastError().find(c.args[0]) == std::string::npos))
            fail(c, errors == 0 ? "no edit failed" : "the last error was: " + probe_.lastError());
        probe_.clearErrors();
        return true;
    }
    if (c.op == "expect-selected-layer") {
        if (!probe_.idle()) return false;
        probe_.collectResults();
        const int want = static_cast<int>(c.numbers[0]);
        if (probe_.selectedLayer() != want)
            fail(c, "layer " + std::to_string(probe_.selectedLayer()) + " is selected, not " + std::to_string(want));
        return true;
    }
    if (c.op == "phase") {
        probe_.setPhase(c.args[0]);
        return true;
    }
    if (c.op == "echo") {
        std::printf("%s\n", c.args.empty() ? "" : c.args[0].c_str());
        std::fflush(stdout);
        return true;
    }
    if (c.op == "quit") {
        done_ = true;
        return true;
    }
    fail(c, "not implemented");
    return true;
}

}  // namespace terrasynth::editor
