#!/usr/bin/env bash
# Constraint fidelity at full size (docs/curves.md): the fidelity tests on 1024x1024 terrains of the
# database of all shared exemplars, 30 random curve cases, 15 points at 10-30 degrees and 30 at 5-40,
# every type painted over the middle quarter (ctest runs them at 512x512 with 20 cases). Expects a
# Release build in build/. Usage: scripts/fidelity.sh [size] [cases]
set -euo pipefail
cd "$(dirname "$0")/.."
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$PWD/build/pocl_cache}"
mkdir -p "$POCL_CACHE_DIR"
TERRASYNTH_FIDELITY_SIZE="${1:-1024}" TERRASYNTH_FIDELITY_CASES="${2:-30}" build/tests/project_fidelity_test
