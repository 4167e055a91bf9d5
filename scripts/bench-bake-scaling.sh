#!/usr/bin/env bash
# Scaling of a sharded bake on this machine (docs/bake.md, "Performance"): for 1, 2 and 4 shards,
# N `terrasynth bake --shard I/N` processes run at once, shard I pinned to core I mod <cores> with one
# worker thread and one PoCL thread (so one shard stands for one single-core node), then the merge.
# Also times one unpinned process on all cores. Prints the median wall time of each over the runs
# and the speed-up over one pinned shard, and from the shards' CPU times (user + sys, which a busy
# shared machine does not inflate) the speed-up idle cores would give: one shard's CPU time over
# max(largest shard, all shards / cores).
#   scripts/bench-bake-scaling.sh [project.tsyn] [runs] [region X,Y,W,H]
# Defaults: data/default.tsyn, 3 runs, 0,0,2048,2048 (256-quad tiles, 4 LODs).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
project=${1:-$here/data/default.tsyn}
runs=${2:-3}
region=${3:-0,0,2048,2048}
binary=${TERRASYNTH:-$here/build/bin/terrasynth}
export POCL_CACHE_DIR=${POCL_CACHE_DIR:-$here/build/pocl_cache}
cores=$(nproc)
work=$(mktemp -d /tmp/bake-scaling.XXXXXX)
trap 'rm -rf "$work"' EXIT
options=(--region "$region" --tile 256 --levels 4 --progress none)

"$binary" bake "$project" -o "$work/prepared" "${options[@]}" --prepare >/dev/null  # database ready

now() { date +%s.%N; }
median() { sort -g | awk '{v[NR]=$1} END {print (NR % 2) ? v[(NR+1)/2] : (v[NR/2] + v[NR/2+1]) / 2}'; }

run_shards() {  # n -> "wall_seconds cpu_of_largest_shard cpu_of_all_shards" (merge excluded)
    local n=$1 world="$work/world" start end i pids=()
    rm -rf "$world"
    start=$(now)
    for ((i = 0; i < n; i++)); do
        POCL_MAX_PTHREAD_COUNT=1 taskset -c $((i % cores)) /usr/bin/time -f '%U %S' -o "$work/cpu.$i" \
            "$binary" bake "$project" -o "$world" "${options[@]}" --shard "$i/$n" --threads 1 >/dev/null &
        pids+=($!)
    done
    for p in "${pids[@]}"; do wait "$p"; done
    end=$(now)
    cat "$work"/cpu.* | awk -v wall="$(awk "BEGIN {print $end - $start}")" \
        '{c = $1 + $2; s += c; if (c > m) m = c} END {print wall, m, s}'
    rm -f "$work"/cpu.*
}

run_whole() {
    local world="$work/whole" start end
    rm -rf "$world"
    start=$(now)
    "$binary" bake "$project" -o "$world" "${options[@]}" >/dev/null
    end=$(now)
    awk "BEGIN {print $end - $start}"
}

echo "bake scaling: region $region, $runs runs each, $cores cores, $(uptime | sed 's/.*load/load/')"
declare -A med
cpu_one=0
for n in 1 2 4; do
    times=() largest=() total=()
    for ((r = 0; r < runs; r++)); do
        read -r wall big all < <(run_shards "$n")
        times+=("$wall") largest+=("$big") total+=("$all")
    done
    med[$n]=$(printf '%s\n' "${times[@]}" | median)
    big=$(printf '%s\n' "${largest[@]}" | median)
    all=$(printf '%s\n' "${total[@]}" | median)
    [ "$n" = 1 ] && cpu_one=$all
    start=$(now)
    "$binary" bake --merge "$work/world" >/dev/null
    merge=$(awk "BEGIN {print $(now) - $start}")
    printf 'shards %d (pinned, 1 thread each): median %.2f s (runs: %s), speed-up %.2fx, merge %.2f s;' \
        "$n" "${med[$n]}" "$(printf '%.2f ' "${times[@]}")" "$(awk "BEGIN {print ${med[1]} / ${med[$n]}}")" "$merge"
    printf ' CPU %.2f s in all, %.2f s in the largest shard: %.2fx on idle cores\n' "$all" "$big" \
        "$(awk "BEGIN {b = $all / $cores; if ($big > b) b = $big; print $cpu_one / b}")"
done
times=()
for ((r = 0; r < runs; r++)); do times+=("$(run_whole)"); done
whole=$(printf '%s\n' "${times[@]}" | median)
printf 'one process, all cores (bake + merge): median %.2f s (runs: %s), speed-up %.2fx\n' "$whole" \
    "$(printf '%.2f ' "${times[@]}")" "$(awk "BEGIN {print ${med[1]} / $whole}")"
