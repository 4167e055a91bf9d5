#!/usr/bin/env bash
# Same inputs and seed, same bits: runs two builds' `terrasynth` on the same cases and compares
# their outputs byte for byte (cmp). For changes that must not move a bit (refactors, speed-ups).
#
#   scripts/compare_bits.sh BEFORE_BIN_DIR AFTER_BIN_DIR [WORK_DIR]
#
# Cases: the default project (OpenCL, 1024^2, seed 3; and the reference backend at 512^2), a 700x900
# window at an odd origin, the default project with breach drainage, and two one-exemplar databases
# (wn_mackay, glac_sthelens_10m) on both backends, wn_mackay with breach drainage too. Every case
# names its drainage, so builds from either side of the switch to breach by default compare alike.
# Heightmaps are written as raw float32 (.f32) so that no quantisation hides a difference; the
# exemplar-coordinate maps are compared too.
# Each build builds its own databases (the database build is compared as well).
# Exit 0: every case identical. Exit 1: a case differs (named). Exit 2: usage or a failed run.
set -euo pipefail
if [ $# -lt 2 ]; then
  echo "usage: $0 BEFORE_BIN_DIR AFTER_BIN_DIR [WORK_DIR]" >&2
  exit 2
fi
before=$(cd "$1" && pwd)
after=$(cd "$2" && pwd)
root=$(cd "$(dirname "$0")/.." && pwd)
work=${3:-$(mktemp -d /tmp/compare_bits.XXXXXX)}
mkdir -p "$work"
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$root/build/pocl_cache}"
mkdir -p "$POCL_CACHE_DIR"
shared="$root/../shared/exemplars"

run_build() {  # label bin_dir
  local label=$1 bin=$2 out="$work/$1"
  mkdir -p "$out"
  "$bin/terrasynth" db build "$root/data/exemplars" -o "$out/default.tsdb" -q
  "$bin/terrasynth" db build "$shared/wn_mackay.png" -o "$out/mackay.tsdb" -q
  "$bin/terrasynth" db build "$shared/glac_sthelens_10m.png" -o "$out/sthelens.tsdb" -q
  # The project reads its database from the exemplar list; --db keeps each build on its own file.
  local s="$bin/terrasynth synth"
  $s --db "$out/default.tsdb" -o "$out/default_cl.f32" --seed 3 --sources "$out/default_cl_src.png" --drainage off
  $s --db "$out/default.tsdb" -o "$out/default_ref.f32" --seed 3 --size 512x512 --backend reference --drainage off
  $s --db "$out/default.tsdb" -o "$out/window_cl.f32" --seed 3 --size 700x900 --origin 333,-517 --drainage off
  $s --db "$out/default.tsdb" -o "$out/breach_cl.f32" --seed 5 --drainage breach
  $s --db "$out/mackay.tsdb" -o "$out/mackay_cl.f32" --seed 3 --drainage off
  $s --db "$out/mackay.tsdb" -o "$out/mackay_ref.f32" --seed 3 --size 384x384 --backend reference --drainage off
  $s --db "$out/mackay.tsdb" -o "$out/mackay_breach_cl.f32" --seed 3 --drainage breach
  $s --db "$out/sthelens.tsdb" -o "$out/sthelens_cl.f32" --seed 4 --drainage off
  $s --db "$out/sthelens.tsdb" -o "$out/sthelens_ref.f32" --seed 4 --size 384x384 --backend reference --drainage off
}

run_build before "$before" >"$work/before.log" 2>&1 || { echo "before build's run failed: $work/before.log" >&2; exit 2; }
run_build after "$after" >"$work/after.log" 2>&1 || { echo "after build's run failed: $work/after.log" >&2; exit 2; }

status=0
for f in "$work"/before/*; do
  name=$(basename "$f")
  case "$name" in *.json) continue ;; esac  # sidecars carry timestamps and paths
  if cmp -s "$f" "$work/after/$name"; then
    echo "same     $name"
  else
    echo "DIFFERS  $name"
    status=1
  fi
done
exit $status
