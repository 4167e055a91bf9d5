#!/usr/bin/env bash
# Runs both synthesis backends under valgrind over the crafted databases of issue 20: every broken
# file the database tests write (build/test_tmp/db_hardening_*/broken.tsdb: the loader must refuse
# each, exit 1; their unbroken control must synthesize) and the accepted database with a terrain type no pixel has, painted over a project
# (build/test_tmp/cl_hardening_files/phantom.tsyn: must synthesize, exit 0). Any valgrind error
# fails the run. Run ctest first (db_hardening_test, cl_hardening_test) to write the files.
#   scripts/valgrind_databases.sh [build]
set -uo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
bin=$build/bin/terrasynth
tmp=$build/test_tmp
out=$(mktemp -d)
export POCL_CACHE_DIR=$PWD/$build/pocl_cache
status=0
check() {  # expected exit code, then the terrasynth arguments
  local expected=$1; shift
  local log=$out/log
  valgrind --quiet --error-exitcode=99 --leak-check=no --suppressions=scripts/valgrind.supp "$bin" "$@" > "$log" 2>&1
  local code=$?
  if [ "$code" -ne "$expected" ]; then
    echo "FAIL (exit $code, expected $expected): terrasynth $*"; sed 's/^/    /' "$log" | head -30; status=1
  else
    echo "ok   (exit $code): terrasynth $* -- $(grep -m1 -o 'terrasynth synth: .*' "$log" | cut -c1-110)"
  fi
}
shopt -s nullglob
files=("$tmp"/db_hardening_*/broken.tsdb)
[ ${#files[@]} -gt 0 ] && [ -f "$tmp/cl_hardening_files/phantom.tsyn" ] || { echo "run ctest first"; exit 1; }
for backend in reference opencl; do
  for db in "${files[@]}"; do
    expected=1
    [[ $db == *db_hardening_untouched/* ]] && expected=0  # the tests' control: the same database unbroken
    check $expected synth --db "$db" --size 24x24 --backend "$backend" -o "$out/o.png"
  done
  check 0 synth "$tmp/cl_hardening_files/phantom.tsyn" --backend "$backend" -o "$out/phantom.png"
done
rm -rf "$out"
exit $status
