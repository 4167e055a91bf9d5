// The game itself: window, world, frame loop, statistics. Private to the game.
#pragma once

#include <chrono>

#include "terrasynth/project.h"
#include "terrasynth_game/game_options.h"

namespace terrasynth::game {

// Runs the game with a project that passed checkBeforeWindow. Returns the process exit code: 0 when
// the window was closed, Esc pressed or the autopilot's time ran out (every worker joined), 2 when
// the world could not be made (the reason printed on stderr).
int runGame(const GameOptions& options, Project project, std::chrono::steady_clock::time_point process_start);

}  // namespace terrasynth::game
