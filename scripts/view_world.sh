#!/usr/bin/env bash
# Shows a baked 3D Tiles world (terrasynth bake, docs/bake.md) in a browser: serves WORLD_DIR, CesiumJS
# and a small viewer page on 127.0.0.1 and opens it. Nothing is fetched from the network (no Cesium
# ion, no imagery): the world stands on a bare ellipsoid.
#
#   scripts/view_world.sh WORLD_DIR [--port 8080] [--no-open]
#   scripts/view_world.sh WORLD_DIR --screenshot OUT.png    # headless Chromium, then exit
#
# Needs node and `npm ci --prefix scripts` (cesium, playwright-core); --screenshot needs Debian's
# chromium (scripts/setup.sh installs both).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
usage() { echo "usage: $0 WORLD_DIR [--port N] [--no-open] | WORLD_DIR --screenshot OUT.png" >&2; exit 2; }
[ $# -ge 1 ] || usage
world=$1; shift
port=8080 open=--open shot=""
while [ $# -gt 0 ]; do
  case "$1" in
    --port) port=${2:?}; shift 2 ;;
    --no-open) open=""; shift ;;
    --screenshot) shot=${2:?}; shift 2 ;;
    *) usage ;;
  esac
done
[ -f "$world/tileset.json" ] || { echo "$0: $world/tileset.json: not found (bake a world: terrasynth bake project.tsyn -o $world)" >&2; exit 2; }
command -v node >/dev/null || { echo "$0: node is not installed (scripts/setup.sh)" >&2; exit 2; }
[ -f "$here/node_modules/cesium/Build/Cesium/Cesium.js" ] || {
  echo "$0: CesiumJS is not installed: run npm ci --prefix scripts" >&2; exit 2; }
if [ -n "$shot" ]; then
  exec node "$here/viewer/screenshot.mjs" "$world" "$shot"
fi
exec node "$here/viewer/serve.mjs" "$world" --port "$port" $open
