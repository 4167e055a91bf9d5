#!/usr/bin/env bash
# Configures and builds terrasynth in ./build (Release, 2 jobs by default).
#
#   bash scripts/build.sh        everything: the library, the CLI, the plugin, the editor, the game,
#                                the Python module (when pybind11 is there), the tests and benchmarks
#   bash scripts/build.sh demo   the same without the tests and benchmarks (scripts/demo.sh: they are
#                                most of the build); a later plain run adds them in the same folder
set -euo pipefail
cd "$(dirname "$0")/.."
case "${1:-all}" in
  all) suite=ON ;;
  demo) suite=OFF ;;
  *) echo "build: unknown profile '$1' (expected demo, or nothing for everything)" >&2; exit 2 ;;
esac
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DTERRASYNTH_BUILD_TESTS=$suite -DTERRASYNTH_BUILD_BENCH=$suite >/dev/null
cmake --build build -j"${JOBS:-2}"
