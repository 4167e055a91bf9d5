// Private: playing a --script (terrasynth_editor/script.h). The player does what a script says
// through EditorActions, as the panels and shortcuts do, and injects pointer and key input into the
// host, which reaches ImGui, the camera and the tools the way real input does, one input step per
// frame. What it waits for and checks it asks an EditorProbe. Main (UI) thread only.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <imgui.h>

#include "editor_actions.h"
#include "terrasynth_editor/script.h"
#include "terrasynth_host/host_window.h"

namespace terrasynth::editor {

// What a script may wait for and check, besides what it does.
class EditorProbe {
public:
    virtual ~EditorProbe() = default;
    virtual bool ready() const = 0;  // the session is open and its terrain shown
    // No edit queued or running, the terrain has every tile it wants, every input reached the screen.
    virtual bool settled() const = 0;
    virtual bool idle() const = 0;  // no edit queued or running
    // Takes the results of finished edits now (their errors are counted, the view is updated).
    virtual void collectResults() = 0;
    virtual int errorsSinceCheck() const = 0;  // failed edits since the start or clearErrors()
    virtual const std::string& lastError() const = 0;
    virtual void clearErrors() = 0;
    virtual bool autosaveHoldsTheLastEdit() const = 0;
    virtual int selectedLayer() const = 0;  // the layer panel's selection, -1 when none
    // A panel item or a 3D handle drawn this frame: its rectangle (min x, min y, max x, max y).
    virtual std::optional<ImVec4> itemRect(const std::string& id) const = 0;
    // Labels the following frames in the --stats report.
    virtual void setPhase(const std::string& name) = 0;
};

class ScriptPlayer {
public:
    // `path` names the script in messages.
    ScriptPlayer(std::vector<ScriptCommand> script, std::string path, EditorActions& editor, EditorProbe& probe,
                 host::HostWindow& host);

    // Runs commands until one waits or injects input (once per frame, after the frame's panels).
    void step();
    // The script ended (its last command, `quit`, or a failure), or stop() was called.
    bool done() const { return done_; }
    bool failed() const { return failed_; }
    void stop() { done_ = true; }

private:
    bool run(const ScriptCommand& c);  // false: call again next frame
    void fail(const ScriptCommand& c, const std::string& why);

    std::vector<ScriptCommand> script_;
    std::string path_;
    EditorActions& editor_;
    EditorProbe& probe_;
    host::HostWindow& host_;

    size_t pc_ = 0;
    // The state of the command being run across frames.
    struct Wait {
        bool started = false;
        int frames = 0;
        double until_s = 0.0, deadline_s = 0.0;
        int drag_step = -1;
        osg::Vec2d drag_from;
        int settle_frames = 0;
        int errors_before = 0;
    } wait_;
    bool yield_ = false;  // the command injected input: the next command waits for the next frame
    bool done_ = false, failed_ = false;
};

}  // namespace terrasynth::editor
