#!/usr/bin/env bash
# Fuzzes the libFuzzer targets of tests/fuzz (issue 20): builds them with clang, ASan and UBSan in
# build-fuzz/ and runs each for FUZZ_SECONDS (default 600). New interesting inputs collect in
# build-fuzz/corpus/<target>/ (the committed seeds in tests/fuzz/corpus/<target>/ are read, never
# written); crashes, leaks and timeouts land in build-fuzz/findings/<target>/ and the run fails.
#   scripts/fuzz.sh                          # every target, 10 minutes each, one after the other
#   FUZZ_TARGETS="database project" FUZZ_SECONDS=60 scripts/fuzz.sh
# Each target's last lines (executions, coverage, time) are in build-fuzz/fuzz_<target>.log.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${FUZZ_SECONDS:-600}
read -r -a targets <<< "${FUZZ_TARGETS:-exemplar_png exemplar_f32 database project cli_flags edit_sidecar}"
cmake -S . -B build-fuzz -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DTERRASYNTH_FUZZ=ON -DTERRASYNTH_SANITIZE=address,undefined -DTERRASYNTH_WITH_OPENCL=OFF \
  -DTERRASYNTH_BUILD_PLUGIN=OFF -DTERRASYNTH_BUILD_HOST=OFF -DTERRASYNTH_BUILD_EDITOR=OFF -DTERRASYNTH_BUILD_GAME=OFF \
  -DTERRASYNTH_BUILD_BENCH=OFF >/dev/null
cmake --build build-fuzz -j"${JOBS:-2}" --target "${targets[@]/#/fuzz_}"
export ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
status=0
for t in "${targets[@]}"; do
  mkdir -p "build-fuzz/corpus/$t" "build-fuzz/findings/$t"
  echo "fuzz: $t for ${seconds} s"
  # -timeout: an input taking 20 s is a cost explosion; -rss_limit_mb: so is one taking 2 GB.
  if ! "build-fuzz/tests/fuzz/fuzz_$t" "build-fuzz/corpus/$t" "tests/fuzz/corpus/$t" -max_total_time="$seconds" \
      -timeout=20 -rss_limit_mb=2048 -print_final_stats=1 -close_fd_mask=3 \
      -artifact_prefix="build-fuzz/findings/$t/" > "build-fuzz/fuzz_$t.log" 2>&1; then
    echo "fuzz: $t FAILED, see build-fuzz/fuzz_$t.log and build-fuzz/findings/$t/"
    status=1
  fi
  grep -E "^stat::(number_of_executed_units|average_exec_per_sec|peak_rss_mb)|^#[0-9]+ *DONE" "build-fuzz/fuzz_$t.log" || true
done
exit $status
