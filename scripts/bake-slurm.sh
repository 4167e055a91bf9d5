#!/usr/bin/env bash
# Bakes a project into a 3D Tiles tileset on a Slurm cluster (docs/bake.md):
#   scripts/bake-slurm.sh project.tsyn world/ --shards N [--cpus-per-task C] [--partition P]
#                         [--logs DIR] [--wait] [-- BAKE OPTIONS...]
# submits three steps, each waiting for the one before to succeed (--dependency=afterok):
#   1. prepare: `terrasynth bake --prepare` builds the project's database once (or finds it) and
#      writes world/bake.json, so the shards only read the database from the shared folder;
#   2. an array of N tasks: `terrasynth bake --shard $SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT`,
#      each with all the cores it was given (--threads $SLURM_CPUS_PER_TASK);
#   3. merge: `terrasynth bake --merge world/` writes world/tileset.json.
# The project, its database and the output folder must be on a filesystem every node sees. Re-running
# the script after a failure redoes only the missing tiles. Job logs go to DIR (default:
# <world>.slurm-logs/). Prints the job ids; with --wait, waits for the merge and exits with its
# status. TERRASYNTH names the binary (default: build/bin/terrasynth of this checkout, else the one
# on PATH); SBATCH_ARGS adds options to every sbatch (e.g. --account=...).
set -euo pipefail

usage() {
    sed -n '2,16p' "$0" | sed 's/^# \{0,1\}//' >&2
    exit 2
}

[ $# -ge 2 ] || usage
project=$1
world=$2
shift 2
shards=""
cpus=2
partition=""
logs=""
wait=0
while [ $# -gt 0 ]; do
    case "$1" in
        --shards) shards=${2:-}; shift 2 ;;
        --cpus-per-task) cpus=${2:-}; shift 2 ;;
        --partition) partition=${2:-}; shift 2 ;;
        --logs) logs=${2:-}; shift 2 ;;
        --wait) wait=1; shift ;;
        --) shift; break ;;
        *) echo "bake-slurm: unknown option $1" >&2; usage ;;
    esac
done
bake_options=("$@")

if ! [[ "$shards" =~ ^[0-9]+$ ]] || [ "$shards" -lt 1 ]; then
    echo "bake-slurm: --shards N needs N >= 1, got '${shards}'" >&2
    exit 2
fi
if ! [[ "$cpus" =~ ^[0-9]+$ ]] || [ "$cpus" -lt 1 ]; then
    echo "bake-slurm: --cpus-per-task needs a positive number, got '${cpus}'" >&2
    exit 2
fi
[ -f "$project" ] || { echo "bake-slurm: $project: no such project file" >&2; exit 2; }
command -v sbatch >/dev/null 2>&1 || { echo "bake-slurm: sbatch not found (install slurm-client)" >&2; exit 2; }

here=$(cd "$(dirname "$0")/.." && pwd)
binary=${TERRASYNTH:-}
if [ -z "$binary" ]; then
    if [ -x "$here/build/bin/terrasynth" ]; then binary="$here/build/bin/terrasynth"; else binary=$(command -v terrasynth || true); fi
fi
[ -n "$binary" ] && [ -x "$binary" ] || { echo "bake-slurm: terrasynth binary not found (set TERRASYNTH)" >&2; exit 2; }

absolute() { (cd "$(dirname "$1")" && echo "$(pwd)/$(basename "$1")"); }
project=$(absolute "$project")
mkdir -p "$(dirname "$world")"
world=$(absolute "$world")
logs=${logs:-${world%/}.slurm-logs}
mkdir -p "$logs"

# The shell words of a command, quoted for --wrap.
quoted() { printf '%q ' "$@"; }
bake=$(quoted "$binary" bake "$project" -o "$world" "${bake_options[@]}")

common=(--parsable --kill-on-invalid-dep=yes)
[ -n "$partition" ] && common+=(--partition="$partition")
# shellcheck disable=SC2206
[ -n "${SBATCH_ARGS:-}" ] && common+=(${SBATCH_ARGS})

prepare=$(sbatch "${common[@]}" --job-name=terrasynth-prepare --cpus-per-task="$cpus" \
    --output="$logs/prepare.log" --wrap "$bake --prepare --progress none")
array=$(sbatch "${common[@]}" --job-name=terrasynth-bake --dependency="afterok:$prepare" \
    --array="0-$((shards - 1))" --cpus-per-task="$cpus" --output="$logs/shard-%a.log" \
    --wrap "$bake --shard \$SLURM_ARRAY_TASK_ID/\$SLURM_ARRAY_TASK_COUNT --threads \$SLURM_CPUS_PER_TASK --progress lines")
merge_command=$(quoted "$binary" bake --merge "$world")
merge_args=("${common[@]}" --job-name=terrasynth-merge --dependency="afterok:$array" --output="$logs/merge.log")
if [ "$wait" = 1 ]; then
    echo "bake-slurm: prepare job $prepare, shard array $array (${shards} tasks), merge waiting; logs in $logs"
    set +e
    sbatch "${merge_args[@]}" --wait --wrap "$merge_command" >/dev/null
    status=$?
    set -e
    if [ $status -eq 0 ]; then
        echo "bake-slurm: merged $world/tileset.json"
    else
        echo "bake-slurm: the bake failed (merge job status $status); see $logs" >&2
    fi
    exit $status
fi
merge=$(sbatch "${merge_args[@]}" --wrap "$merge_command")
echo "bake-slurm: prepare job $prepare, shard array $array (${shards} tasks), merge job $merge; logs in $logs"
