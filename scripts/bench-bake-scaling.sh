#!/usr/bin/env bash
# Scaling of a sharded bake on this machine (docs/bake.md, "Performance"): for 1, 2 and 4 shards,
# N `terrasynth bake --shard I/N` processes run at once, shard I pinned to core I mod <cores> with one
# worker thread and one PoCL thread (so one shard stands for one single-core node), then the merge.
# Also times one unpinned process on all cores. Prints the median wall time of each over the runs
# and the speed-up over one pinned shard.
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

run_shards() {  # n -> wall seconds of the shards (merge excluded)
    local n=$1 world="$work/world" start end i pids=()
    rm -rf "$world"
    start=$(now)
    for ((i = 0; i < n; i++)); do
        POCL_MAX_PTHREAD_COUNT=1 taskset -c $((i % cores)) "$binary" bake "$project" -o "$world" "${options[@]}" \
            --shard "$i/$n" --threads 1 >/dev/null &
        pids+=($!)
    done
    for p in "${pids[@]}"; do wait "$p"; done
    end=$(now)
    echo "$end - $start" | bc -l
}

run_whole() {
    local world="$work/whole" start end
    rm -rf "$world"
    start=$(now)
    "$binary" bake "$project" -o "$world" "${options[@]}" >/dev/null
    end=$(now)
    echo "$end - $start" | bc -l
}

echo "bake scaling: region $region, $runs runs each, $cores cores, $(uptime | sed 's/.*load/load/')"
declare -A med
for n in 1 2 4; do
    times=()
    for ((r = 0; r < runs; r++)); do times+=("$(run_shards "$n")"); done
    med[$n]=$(printf '%s\n' "${times[@]}" | median)
    start=$(now)
    "$binary" bake --merge "$work/world" >/dev/null
    merge=$(echo "$(now) - $start" | bc -l)
    printf 'shards %d (pinned, 1 thread each): median %.2f s (runs: %s), speed-up %.2fx, merge %.2f s\n' \
        "$n" "${med[$n]}" "$(printf '%.2f ' "${times[@]}")" "$(echo "${med[1]} / ${med[$n]}" | bc -l)" "$merge"
done
times=()
for ((r = 0; r < runs; r++)); do times+=("$(run_whole)"); done
whole=$(printf '%s\n' "${times[@]}" | median)
printf 'one process, all cores (bake + merge): median %.2f s (runs: %s), speed-up %.2fx\n' "$whole" \
    "$(printf '%.2f ' "${times[@]}")" "$(echo "${med[1]} / $whole" | bc -l)"
