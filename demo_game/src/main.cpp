// terrasynth_game: fly over an endless world synthesized from a seed while you fly (demo_game/).
// Everything checkable is checked before a window opens; bad input exits 2 with a message.
#include <chrono>
#include <cstdio>
#include <optional>

#include "game_session.h"
#include "terrasynth_game/game_options.h"

int main(int argc, char** argv) {
    const auto start = std::chrono::steady_clock::now();
    using namespace terrasynth::game;
    std::optional<int> exit_code;
    std::optional<GameOptions> options = parseGameOptions(argc, argv, &exit_code, TERRASYNTH_GAME_DEFAULT_PROJECT);
    if (!options) return exit_code.value_or(2);
    auto project = checkBeforeWindow(*options);
    if (!project) {
        std::fprintf(stderr, "terrasynth_game: %s\n", project.message().c_str());
        return 2;
    }
    return runGame(*options, std::move(*project), start);
}
