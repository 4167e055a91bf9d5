#!/usr/bin/env bash
# The editor's latency benchmark (issue 14): terrasynth_editor in a 1280x720 window under Xvfb (Mesa
# llvmpipe, no GPU) on the default 1024^2 project, driven by editor_ui/scripts/latency.script (a point
# drag, a band slider drag, a curve widget drag, idle frames). Writes out/editor_bench/stats.json
# (medians, p95, frame split into main-thread work and the GL draw, tiles rebuilt) and prints a summary.
# Usage: scripts/editor_bench.sh [build dir] [editor options...], e.g. --drag-preview-levels 0
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
shift $(( $# > 0 ? 1 : 0 ))
out=out/editor_bench
mkdir -p "$out"
export POCL_CACHE_DIR=${POCL_CACHE_DIR:-$PWD/$build/pocl_cache}
mkdir -p "$POCL_CACHE_DIR"
# The default project, written in out/ so that its autosave lands there (its database cache is the
# one data/default.tsyn uses).
cat > "$out/bench.tsyn" <<JSON
{"format": "terrasynth-project", "version": 1, "exemplars": ["$PWD/data/exemplars"],
 "database": "$PWD/data/default.tsdb", "database_levels": 6, "meters_per_pixel": 0,
 "size": [1024, 1024], "origin": [0, 0],
 "synthesis": {"seed": 1, "jitter": 0.4, "correction_passes": 2, "coarsest_level": -1},
 "constraints": {}, "layers": []}
JSON
rm -f "$out"/bench.autosave.*
display=()
if [ -z "${DISPLAY:-}" ]; then display=(xvfb-run -a -s "-screen 0 1280x720x24"); fi
"${display[@]}" "$build/bin/terrasynth_editor" "$out/bench.tsyn" --size 1280x720 \
  --script editor_ui/scripts/latency.script --stats "$out/stats.json" "$@" > "$out/editor.log"
/usr/bin/python3 - "$out/stats.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
print("renderer:", j["renderer"], " window:", j["window"], " extent:", j["extent"])
for kind, lat in j["latency"].items():
    s, v, a = lat["event_to_swapped_ms"], lat["event_to_shown_ms"], lat["event_to_applied_ms"]
    print(f"{kind:12s} n={s['count']:3d}  event->swapped median {s['median']:6.1f} p95 {s['p95']:6.1f}"
          f" | ->applied median {a['median']:6.1f} | ->shown median {v['median']:6.1f} p95 {v['p95']:6.1f}"
          f" | edit {lat['edit_ms']['median']:5.1f} queued {lat['queued_ms']['median']:5.1f} ms")
for phase, f in j["frames"].items():
    print(f"{phase:12s} frames={f['frame_ms']['count']:4d}  frame median {f['frame_ms']['median']:6.1f} p95 {f['frame_ms']['p95']:6.1f}"
          f" | main thread median {f['main_thread_ms']['median']:5.2f} p95 {f['main_thread_ms']['p95']:5.2f}"
          f" | GL draw median {f['draw_ms']['median']:6.1f} overlay {f['overlay_ms']['median']:5.2f} ms")
t = j["tiles"]
print(f"tiles: {t['edits']} edits, rebuilt {t['rebuilt']} (swapped {t['swapped']}, unchanged {t['rebuilt_unchanged']})"
      f" of {t['touching_changed_window']} marked as touching the changed windows; {t['in_view']} drawn summed over edits;"
      f" mean build {t['mean_build_ms']:.1f} ms since start-up, {t['edit_mean_build_ms']:.1f} ms while editing"
      f" (heights {t['edit_mean_heights_ms']:.1f} ms)")
print("autosave:", j["autosave_ms"])
PY
