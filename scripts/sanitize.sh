#!/usr/bin/env bash
# Builds the project with sanitizers and runs the test suite under them (issue 20):
#   ASan + UBSan in build-asan/ (-DTERRASYNTH_SANITIZE=address,undefined), TSan in build-tsan/
#   (-DTERRASYNTH_SANITIZE=thread). Any report fails the run (UBSan halts on its first finding).
#
#   scripts/sanitize.sh                 # both builds, whole suite
#   scripts/sanitize.sh address         # ASan + UBSan only
#   scripts/sanitize.sh thread          # TSan only
#   SANITIZE_TESTS='^(Core|Db)' scripts/sanitize.sh address   # a ctest -R subset
#   SANITIZE_SCOPE=runtime scripts/sanitize.sh address   # runtime and CLI only: no plugin, no
#                                                        # editor
#   SANITIZE_SCOPE=input scripts/sanitize.sh address     # the runtime's and CLI's bad-input
#                                                        # programs and the fuzz corpus (what CI
#                                                        # runs, see scripts/test.sh)
#   SANITIZE_SCOPE=threads scripts/sanitize.sh thread    # the code threads share: the plugin's
#                                                        # paging, workers and tile store, the edit
#                                                        # thread, the session's readers, the game's
#                                                        # ground cache, the runtime's workers
#                                                        # (THREAD_TEST_PROGRAMS; what CI runs)
#   SANITIZE_EXCLUDE_LABEL='survey|costly' scripts/sanitize.sh address   # ctest -LE: without the
#                                                        # surveys and the costly tests
#                                                        # (tests/CMakeLists.txt; CI leaves both out)
#
# PoCL (the OpenCL runtime the cl_ tests use) is not instrumented: its threads and LLVM allocations
# are outside our code, so leak checking skips it and TSan ignores races inside it (tsan.supp).
set -euo pipefail
cd "$(dirname "$0")/.."
mode=${1:-all}
jobs=${JOBS:-2}

run() {
  local name=$1 sanitizers=$2 dir=build-$1
  local start=$SECONDS
  # Every scope sets all of these, so a build folder configured for one scope serves another.
  local front_ends=ON programs="" exclude=() select=${SANITIZE_TESTS:-} targets=()
  case "${SANITIZE_SCOPE:-all}" in
    all) ;;
    runtime) front_ends=OFF ;;
    input) front_ends=OFF programs=$INPUT_TEST_PROGRAMS
      exclude=(-E '^TestDatabases[.]Shared') ;;  # no bad-input program reads the shared database
    threads) programs=$THREAD_TEST_PROGRAMS select=${SANITIZE_TESTS:-$THREAD_TESTS}
      # Only the test programs (and what they run: the osgDB module, the editor and the game), not
      # the CLI, the viewers or the bench.
      targets=(--target $(echo "$THREAD_TEST_PROGRAMS" | tr -d '^$()' | tr '|' ' ')) ;;
    *) echo "sanitize.sh: SANITIZE_SCOPE must be all, runtime, input or threads, not '$SANITIZE_SCOPE'" >&2; return 2 ;;
  esac
  cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTERRASYNTH_SANITIZE="$sanitizers" \
    -DTERRASYNTH_BUILD_BENCH=OFF -DTERRASYNTH_BUILD_PLUGIN=$front_ends -DTERRASYNTH_BUILD_HOST=$front_ends \
    -DTERRASYNTH_BUILD_EDITOR=$front_ends -DTERRASYNTH_BUILD_GAME=$front_ends \
    -DTERRASYNTH_TEST_PROGRAMS="$programs" >/dev/null
  cmake --build "$dir" -j"$jobs" "${targets[@]}"
  local built=$SECONDS
  export POCL_CACHE_DIR="$PWD/$dir/pocl_cache"
  mkdir -p "$POCL_CACHE_DIR"
  # PoCL's cache is keyed by the kernels' source, options and device, not by the program that asks:
  # the kernels the plain build compiled (scripts/test.sh runs it first) serve the sanitized one.
  if [ -d build/pocl_cache ] && [ -z "$(ls -A "$POCL_CACHE_DIR")" ]; then
    cp -a build/pocl_cache/. "$POCL_CACHE_DIR"/
  fi
  if [ "$name" = tsan ]; then
    # PoCL compiles the kernels with clang on its own threads, and TSan reports races inside that
    # uninstrumented compiler (string appends, handed-over locks) that no suppression by library
    # catches. So the kernels come from PoCL's cache in the tests: the copy above, topped up by one
    # synthesis test of the plain build (not instrumented, seconds) for whatever it lacks.
    if [ -x build/tests/cl_synthesis_test ]; then
      build/tests/cl_synthesis_test --gtest_filter='Synthesis.AdjacentWindowsEqualHalvesOfTheWholeWindow' >/dev/null 2>&1 || true
    else
      echo "sanitize.sh: no plain build (build/tests/cl_synthesis_test) to compile the kernels outside TSan; PoCL's compiler threads may be reported" >&2
    fi
  fi
  local status=0
  ctest --test-dir "$dir" --output-on-failure -j"$jobs" --timeout 3000 ${select:+-R "$select"} \
    ${SANITIZE_EXCLUDE_LABEL:+-LE "$SANITIZE_EXCLUDE_LABEL"} "${exclude[@]}" || status=$?
  # LeakSanitizer's tracer now and then crashes by itself at exit, after a passing test
  # (sanitizer_tool_crashes.py says why); such tests, and only when every failure is one, run once more.
  if [ "$status" -ne 0 ] && /usr/bin/python3 scripts/sanitizer_tool_crashes.py "$dir"; then
    echo "sanitize $name: rerunning once the tests the sanitizer itself crashed in"
    status=0
    ctest --test-dir "$dir" --output-on-failure --rerun-failed --timeout 3000 || status=$?
  fi
  echo "sanitize $name: build $((built - start)) s, tests $((SECONDS - built)) s, status $status"
  return $status
}

# The bad-input suite (SANITIZE_SCOPE=input): the programs that feed the readers, parsers and
# writers corrupt, hostile or absurd input, plus the replay of the fuzz corpus (always built).
INPUT_TEST_PROGRAMS='hardening|hostile|sidecar|^core_io_test$|^core_transaction_test$|^project_format_test$|^db_dem_cli_test$|^db_test_databases_test$|^python_tests$'
# The threads suite (SANITIZE_SCOPE=threads): the programs whose code runs on several threads at
# once, and of them the tests that drive those threads (the others are single-threaded runs of the
# same programs, minutes under TSan).
THREAD_TEST_PROGRAMS='^(plugin_paging_test|plugin_pool_internal_test|plugin_store_internal_test|editor_worker_test|project_session_test|game_flight_test|core_workers_internal_test|db_test_databases_test)$'
THREAD_TESTS='^(PluginPaging|PluginPool|PluginStore|EditorWorker|EditorLatency|GameGround|CoreWorkers)[.]|^EditSession[.]TilesReadOnTwoThreads|^TestDatabases[.]Default'
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:detect_stack_use_after_return=1:strict_string_checks=1
export LSAN_OPTIONS=suppressions=$PWD/scripts/lsan.supp:print_suppressions=0
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
export TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1:suppressions=$PWD/scripts/tsan.supp
status=0
if [ "$mode" = all ] || [ "$mode" = address ]; then run asan address,undefined || status=1; fi
if [ "$mode" = all ] || [ "$mode" = thread ]; then run tsan thread || status=1; fi
exit $status
