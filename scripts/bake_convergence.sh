#!/usr/bin/env bash
# A bake is safe to run twice at once and to kill (issue 37; docs/bake.md, "Running it again"):
# bakes one region cleanly, then
#   1. two processes bake the same shard at once (a requeued Slurm task beside its first attempt),
#      the second started once the first has written tiles; then the other shard and the merge;
#   2. a whole bake is killed with SIGKILL once it has written tiles, and run again;
# and compares each world with the clean one by `diff -rq` (no temporary left, every byte equal).
#   scripts/bake_convergence.sh [TERRASYNTH]      # default: build/bin/terrasynth
# Exit 0 when both worlds equal the clean one; the bakes' logs are printed when one fails.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=$(realpath "${1:-build/bin/terrasynth}")
work=$(mktemp -d "${TMPDIR:-/tmp}/bake_convergence.XXXXXX")
trap 'rm -rf "$work"' EXIT
cat > "$work/world.tsyn" <<JSON
{"format": "terrasynth-project", "version": 1, "exemplars": ["$PWD/data/exemplars/orom_alaska.png"],
 "database_levels": 4, "size": [512, 512], "synthesis": {"seed": 9}}
JSON
options=(--region 0,0,513,513 --tile 32 --levels 3 --progress none)
bake() { "$bin" bake "$work/world.tsyn" "${options[@]}" "$@"; }
# In the background the binary itself, not a subshell running bake(): $! is then the process killed.
bake_bg() { "$bin" bake "$work/world.tsyn" "${options[@]}" "$@" & }
glbs() { find "$1" -name '*.glb' 2>/dev/null | wc -l; }
# Waits (no time window: as long as it takes) until $1 holds at least 3 tiles, or the bake $2 ended.
until_tiles() { while [ "$(glbs "$1")" -lt 3 ] && kill -0 "$2" 2>/dev/null; do sleep 0.05; done; }
start=$SECONDS

bake -o "$work/clean" > "$work/clean.log" 2>&1  # also builds the database cache beside the project
echo "clean bake: $(glbs "$work/clean") tiles, $((SECONDS - start)) s"

status=0
# 1. The same shard twice at once, then the other shard and the merge.
bake_bg -o "$work/twice" --shard 0/2 --threads 1 > "$work/first.log" 2>&1; first=$!
until_tiles "$work/twice" "$first"
bake_bg -o "$work/twice" --shard 0/2 --threads 1 > "$work/second.log" 2>&1; second=$!
ran=0
wait "$first" || ran=1
wait "$second" || ran=1
[ $ran = 0 ] && bake -o "$work/twice" --shard 1/2 > "$work/other.log" 2>&1 || ran=1
[ $ran = 0 ] && "$bin" bake --merge "$work/twice" > "$work/merge.log" 2>&1 || ran=1
[ $ran = 0 ] || { tail -n 5 "$work"/{first,second,other,merge}.log 2>/dev/null || true; status=1; }
if diff -rq "$work/clean" "$work/twice"; then echo "two bakes of one shard at once: identical to the clean bake"
else echo "two bakes of one shard at once: DIFFERENT from the clean bake"; status=1; fi

# 2. Killed with SIGKILL mid-bake, then run again.
bake_bg -o "$work/killed" --threads 1 > "$work/killed.log" 2>&1; victim=$!
until_tiles "$work/killed" "$victim"
kill -KILL "$victim" 2>/dev/null || echo "note: the bake ended before it could be killed"
wait "$victim" 2>/dev/null || true
echo "killed after $(glbs "$work/killed") tiles"
bake -o "$work/killed" > "$work/rerun.log" 2>&1 || { tail -n 5 "$work/rerun.log"; status=1; }
if diff -rq "$work/clean" "$work/killed"; then echo "killed and re-run: identical to the clean bake"
else echo "killed and re-run: DIFFERENT from the clean bake"; status=1; fi

echo "bake_convergence: $((SECONDS - start)) s, status $status"
exit $status
