// terrasynth_editor: the in-engine editor (issue 14). Everything that can be wrong with the input is
// found before a window opens (exit 2 with the loader's message); then one window, one session.
#include <cstdio>
#include <exception>
#include <string>

#include "editor_app.h"
#include "terrasynth/constraints.h"
#include "terrasynth/database.h"
#include "terrasynth/layers.h"
#include "terrasynth/project.h"

namespace {

using namespace terrasynth;
using namespace terrasynth::editor;

// The last line of defence for the whole program (an exception escaping anything becomes a message
// and exit code 1). When terrasynth/guard.h (branch `harden`) is merged, replace this function by
// `using terrasynth::runGuarded;` and include "terrasynth/guard.h".
template <class Body>
int runGuarded(const char* program, Body&& body) {
    try {
        return body();
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "%s: out of memory (std::bad_alloc)\n", program);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: %s\n", program, e.what());
    } catch (...) {
        std::fprintf(stderr, "%s: unknown exception\n", program);
    }
    return kExitFailed;
}

int badInput(const std::string& message) {
    std::fprintf(stderr, "terrasynth_editor: %s\n", message.c_str());
    return kExitBadInput;
}

// The project's database if it is ready to load (a prebuilt one, or a cache whose digest matches the
// exemplars), so the constraints can be checked before the window; null when it must be built (the
// window then shows the build's progress). Errors: unreadable exemplars or database, named.
Result<std::shared_ptr<const ExemplarDatabase>> databaseIfReady(const Project& p) {
    if (p.exemplars.empty()) return openProjectDatabase(p);
    DatabaseBuildOptions o;
    o.levels = p.database_levels;
    o.meters_per_pixel = p.meters_per_pixel;
    auto digest = digestInputs(p.exemplars, o);
    if (!digest) return digest.status();
    auto cached = loadDatabase(p.databaseCachePath());
    if (cached && cached.value()->input_digest == digest.value()) return cached;
    return std::shared_ptr<const ExemplarDatabase>();
}

int run(int argc, char** argv) {
    std::string help;
    auto options = parseEditorOptions(argc, argv, &help);
    if (!options) return badInput(options.message());
    if (!help.empty()) {
        std::printf("%s", help.c_str());
        return kExitOk;
    }
    auto project = loadProject(options->project);
    if (!project) return badInput(project.message());
    std::vector<ScriptCommand> script;
    if (!options->script.empty()) {
        auto parsed = readScript(options->script);
        if (!parsed) return badInput(parsed.message());
        script = std::move(parsed.value());
    }

    // A newer autosave is opened instead with --recover (it is checked like the project).
    std::string recover_from;
    Project to_check = *project;
    if (options->recover) {
        recover_from = newerAutosave(project->path);
        if (recover_from.empty()) {
            std::printf("terrasynth_editor: no autosave newer than %s; opening it\n", project->path.c_str());
        } else if (auto autosaved = loadProject(recover_from); autosaved) {
            to_check = std::move(autosaved.value());
        } else {
            std::fprintf(stderr, "terrasynth_editor: cannot recover: %s; opening the project\n", autosaved.message().c_str());
            recover_from.clear();
        }
    }
    if (auto stack = parseLayerStack(to_check.layers_json, to_check.folder()); !stack)
        return badInput(stack.status().withContext(to_check.path).message());
    auto database = databaseIfReady(to_check);
    if (!database) return badInput(database.status().withContext(to_check.path).message());
    if (database.value()) {
        auto constraints = parseConstraints(to_check.constraints_json, to_check.folder(), *database.value(), to_check.origin_x,
                                            to_check.origin_y, to_check.width, to_check.height);
        if (!constraints) return badInput(constraints.status().withContext(to_check.path).message());
    }

    host::HostOptions h;
    h.width = options->width;
    h.height = options->height;
    h.title = "terrasynth editor: " + project->path;
    h.clear_color = osg::Vec4(options->clear_color[0], options->clear_color[1], options->clear_color[2], 1.0f);
    h.ui_scale = options->ui_scale;
    auto window = host::HostWindow::create(h);
    if (!window) {
        std::fprintf(stderr, "terrasynth_editor: %s\n", window.message().c_str());
        return kExitFailed;
    }
    EditorApp app(**window, *options, std::move(project.value()), std::move(script), database.value(), recover_from);
    return app.run();
}

}  // namespace

int main(int argc, char** argv) {
    return runGuarded("terrasynth_editor", [&] { return run(argc, argv); });
}
