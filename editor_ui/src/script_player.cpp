// Playing a --script (terrasynth_editor/script.h): input goes through the host's injection, one
// step per frame, so scripted runs take the path real input takes.
#include <cmath>
#include <cstdio>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "editor_app.h"
#include "terrasynth/heightfield_io.h"

namespace terrasynth::editor {
namespace {

int buttonOf(const ScriptCommand& c) {
    if (c.args.empty() || c.args[0] == "left") return 0;
    return c.args[0] == "right" ? 1 : 2;
}

bool parseBool(const std::string& v, bool* out) {
    if (v == "1" || v == "true" || v == "on") return *out = true, true;
    if (v == "0" || v == "false" || v == "off") return *out = false, true;
    return false;
}

}  // namespace

void EditorApp::scriptFail(const ScriptCommand& c, const std::string& why) {
    std::fprintf(stderr, "terrasynth_editor: %s:%d: %s: %s\n", options_.script.c_str(), c.line, c.op.c_str(), why.c_str());
    exit_code_ = kExitFailed;
    script_done_ = true;
}

void EditorApp::scriptStep() {
    if (worker_->state() != EditWorker::State::Ready || !terrain_) return;
    while (script_pc_ < script_.size() && !script_done_) {
        script_yield_ = false;
        const bool finished = runScriptCommand(script_[script_pc_]);
        if (finished) {
            ++script_pc_;
            wait_ = ScriptWait{};
        }
        // Injected input reaches the editor at the next beginFrame: one input step per frame.
        if (!finished || script_yield_) return;
    }
    if (script_pc_ >= script_.size()) script_done_ = true;
}

bool EditorApp::runScriptCommand(const ScriptCommand& c) {
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
        wait_.settle_frames = settled() ? wait_.settle_frames + 1 : 0;
        if (wait_.settle_frames >= 3) return true;
        if (now > wait_.deadline_s) scriptFail(c, "the editor did not settle in time");
        return false;
    }
    if (c.op == "view") {
        const GridFrame& f = view_->frame;
        const osg::Vec3d centre(f.worldX(n[0]), f.worldY(n[1]), groundAtPixel(n[0], n[1]));
        if (c.args[0] == "aerial") {
            camera_->setAerial(centre, n[2]);
            free_view_ = false;
        } else {
            camera_->setFree(centre, n[2], n[3], n[4]);
            free_view_ = true;
        }
        return true;
    }
    if (c.op == "tool") {
        const auto t = toolFromName(c.args[0]);
        if (!t) {
            scriptFail(c, "unknown tool '" + c.args[0] + "'");
            return true;
        }
        tool_ = *t;
        drag_ = Drag{};
        return true;
    }
    if (c.op == "set") {
        const std::string& key = c.args[0];
        const std::string& value = c.args[1];
        ToolOptions& o = tool_options_;
        std::map<std::string, float*> floats = {
            {"point.raise", &o.point_raise_m},        {"point.radius", &o.point_radius_px},
            {"point.slope", &o.point_slope_deg},      {"point.slope_dir", &o.point_slope_direction_deg},
            {"curve.height", &o.curve_height_m},      {"curve.reach", &o.curve_reach_px},
            {"brush.radius", &o.brush_radius_px},     {"paste.offset", &o.paste_offset_m},
            {"peak.height", &o.peak_height_m},        {"peak.spread", &o.peak_spread_px},
            {"ridge.height", &o.ridge_height_m},      {"ridge.width", &o.ridge_width_px},
            {"noise.amplitude", &o.noise_amplitude_m}, {"noise.wavelength", &o.noise_wavelength_px}};
        std::map<std::string, bool*> flags = {{"curve.spline", &o.curve_spline}, {"brush.erase", &o.erase},
                                              {"overlay.reach", &show_reach_}};
        if (auto it = floats.find(key); it != floats.end()) {
            char* end = nullptr;
            const double v = std::strtod(value.c_str(), &end);
            if (end == value.c_str() || *end || !std::isfinite(v)) scriptFail(c, "'" + value + "' is not a number");
            else *it->second = static_cast<float>(v);
        } else if (auto f = flags.find(key); f != flags.end()) {
            if (!parseBool(value, f->second)) scriptFail(c, "'" + value + "' is not 0 or 1");
        } else if (key == "curve.preset") {
            if (value == "ridge") o.curve_preset = CurvePreset::Ridge;
            else if (value == "valley") o.curve_preset = CurvePreset::Valley;
            else if (value == "cliff") o.curve_preset = CurvePreset::Cliff;
            else scriptFail(c, "unknown preset '" + value + "' (ridge, valley, cliff)");
        } else if (key == "paint.type") {
            const auto& names = view_->database->type_names;
            const auto it = std::find(names.begin(), names.end(), value);
            if (it == names.end()) scriptFail(c, "the database has no type '" + value + "'");
            else o.paint_type = static_cast<int>(it - names.begin());
        } else {
            scriptFail(c, "unknown option '" + key + "'");
        }
        return true;
    }
    if (c.op == "move") {
        host_.injectMouseMove(n[0], n[1]);
        script_yield_ = true;
        return true;
    }
    if (c.op == "press" || c.op == "release") {
        host_.injectMouseButton(buttonOf(c), c.op == "press");
        script_yield_ = true;
        return true;
    }
    if (c.op == "click") {
        // Press this frame, release the next.
        if (first) {
            host_.injectMouseButton(buttonOf(c), true);
            return false;
        }
        host_.injectMouseButton(buttonOf(c), false);
        script_yield_ = true;
        return true;
    }
    if (c.op == "drag") {
        const int steps = n.size() > 4 ? static_cast<int>(n[4]) : 10;
        if (first) wait_.drag_step = -1;
        const int s = wait_.drag_step++;
        if (s == -1) host_.injectMouseMove(n[0], n[1]);
        else if (s == 0) host_.injectMouseButton(0, true);
        else if (s <= steps) {
            const double f = static_cast<double>(s) / steps;
            host_.injectMouseMove(n[0] + f * (n[2] - n[0]), n[1] + f * (n[3] - n[1]));
        } else {
            host_.injectMouseButton(0, false);
            script_yield_ = true;
            return true;
        }
        return false;
    }
    if (c.op == "item") {
        const auto it = items_.find(c.args[0]);
        if (it == items_.end()) {
            scriptFail(c, "no panel item '" + c.args[0] + "' on screen");
            return true;
        }
        const ImVec4& r = it->second;
        const double dx = n.size() > 1 ? n[0] : 0.0, dy = n.size() > 1 ? n[1] : 0.0;
        host_.injectMouseMove(0.5 * (r.x + r.z) + dx, 0.5 * (r.y + r.w) + dy);
        script_yield_ = true;
        return true;
    }
    if (c.op == "drag-item") {
        // The item is found once, when the drag starts (it may move with what it edits).
        const int steps = n.size() > 2 ? static_cast<int>(n[2]) : 10;
        if (first) {
            const auto it = items_.find(c.args[0]);
            if (it == items_.end()) {
                scriptFail(c, "no item '" + c.args[0] + "' on screen");
                return true;
            }
            const ImVec4& r = it->second;
            wait_.until_s = 0.5 * (r.x + r.z);  // the start, kept in the wait state
            wait_.deadline_s = 0.5 * (r.y + r.w);
            wait_.drag_step = -1;
        }
        const double x0 = wait_.until_s, y0 = wait_.deadline_s;
        const int s = wait_.drag_step++;
        if (s == -1) host_.injectMouseMove(x0, y0);
        else if (s == 0) host_.injectMouseButton(0, true);
        else if (s <= steps) host_.injectMouseMove(x0 + n[0] * s / steps, y0 + n[1] * s / steps);
        else {
            host_.injectMouseButton(0, false);
            script_yield_ = true;
            return true;
        }
        return false;
    }
    if (c.op == "key") {
        int key = 0, mods = 0;
        parseKeySpec(c.args[0], &key, &mods);
        if (first) {
            host_.injectKey(key, true, mods);
            return false;
        }
        host_.injectKey(key, false, mods);
        script_yield_ = true;
        return true;
    }
    if (c.op == "scroll") {
        host_.injectScroll(0.0, n[0]);
        script_yield_ = true;
        return true;
    }
    if (c.op == "screenshot") {
        if (first) {
            host_.requestScreenshot(c.args[0], c.args.size() < 2 || c.args[1] == "ui");
            return false;
        }
        if (!host_.lastScreenshotStatus()) scriptFail(c, host_.lastScreenshotStatus().message());
        return true;
    }
    if (c.op == "save" || c.op == "heights") {
        if (first) {
            wait_.frames = errors_since_check_;  // a new error is this command's
            if (c.op == "save") {
                save(c.args.empty() ? save_path_ : c.args[0]);
            } else {
                EditRequest r;
                r.label = "write heights " + c.args[0];
                r.run = [path = c.args[0]](EditSession& s) -> Result<PixelWindow> {
                    if (Status st = writeHeightfieldF32(path, s.heights()); !st) return st;
                    return PixelWindow{};
                };
                submit(std::move(r));
            }
            return false;
        }
        if (!worker_->idle()) return false;
        onResults();
        if (errors_since_check_ > wait_.frames) scriptFail(c, last_error_);
        return true;
    }
    if (c.op == "undo-all") {
        if (first) wait_.deadline_s = now + 300.0;
        if (!worker_->idle()) return false;
        onResults();
        if (!view_->can_undo) return true;
        if (now > wait_.deadline_s) {
            scriptFail(c, "still undoing after 300 s");
            return true;
        }
        undo();
        return false;
    }
    if (c.op == "wait-autosave") {
        if (first) wait_.deadline_s = now + 60.0;
        if (!autosave_queued_ && autosaved_count_ == worker_->editCount() && worker_->idle()) return true;
        if (now > wait_.deadline_s) scriptFail(c, "no autosave of the current edit within 60 s");
        return false;
    }
    if (c.op == "expect-error" || c.op == "expect-ok") {
        if (!worker_->idle()) return false;
        onResults();
        if (c.op == "expect-ok" && errors_since_check_ > 0) scriptFail(c, "an edit failed: " + last_error_);
        if (c.op == "expect-error" && (errors_since_check_ == 0 || last_error_.find(c.args[0]) == std::string::npos))
            scriptFail(c, errors_since_check_ == 0 ? "no edit failed" : "the last error was: " + last_error_);
        errors_since_check_ = 0;
        return true;
    }
    if (c.op == "phase") {
        setPhase(c.args[0]);
        return true;
    }
    if (c.op == "echo") {
        std::printf("%s\n", c.args.empty() ? "" : c.args[0].c_str());
        std::fflush(stdout);
        return true;
    }
    if (c.op == "quit") {
        script_done_ = true;
        return true;
    }
    scriptFail(c, "not implemented");
    return true;
}

}  // namespace terrasynth::editor
