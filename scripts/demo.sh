#!/usr/bin/env bash
# README command (a): install dependencies, build, and run the main job on the shipped default
# exemplars: build the exemplar database, synthesize a 1024x1024 terrain, write heightmap, hillshade
# and coordinate map to out/, print its realism statistics, export a glTF. The database is written
# where the default project keeps its cache, so the project reuses it.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh demo   # the demo profile: no Blender, Chromium, Slurm, clang, valgrind or Node.js
bash scripts/build.sh demo   # without the tests and benchmarks, which scripts/test.sh adds
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$PWD/build/pocl_cache}"
mkdir -p out "$POCL_CACHE_DIR"
build/bin/terrasynth db build data/exemplars -o data/default.tsdb
build/bin/terrasynth synth data/default.tsyn -o out/terrain.png --preview out/terrain_hillshade.png \
  --sources out/terrain_sources.png
build/bin/terrasynth stats out/terrain.png
build/bin/terrasynth export data/default.tsyn -o out/terrain.glb --lods 3   # + terrain_lod1.glb, terrain_lod2.glb
echo "demo: results in out/ (terrain.png + .json, terrain_hillshade.png, terrain_sources.png, terrain.glb)"
