#!/usr/bin/env bash
# The OpenCL tests and synth_bench on a lent GPU machine (the workplace's `device` tool), in one call.
#
# That machine has no package registry and another distribution, so the binaries are built here and
# carried with the shared libraries they need (scripts/device_pack.sh fills .device/, which git
# ignores), and the GPU's own OpenCL driver is registered with the carried ICD loader.
#   here:   bash scripts/device_pack.sh
#   there:  bash scripts/device_check.sh      (carry .device; results under $OUT)
# Logs and the GPU's synthesis of the default project come back under $OUT for comparison with the
# CPU (PoCL) run here.
set -u
OUT=${OUT:-/tmp/device_out}
mkdir -p "$OUT"
root=$PWD
pack=$root/.device

main() {

# device_pack.sh packs binaries and libraries into one archive: unpack it in place (Python's tarfile
# where tar has no xz).
if [ -f "$pack/payload.tar.xz" ]; then
  python3 -c 'import sys, tarfile; tarfile.open(sys.argv[1]).extractall(sys.argv[2])' "$pack/payload.tar.xz" "$pack" ||
    tar -C "$pack" -xJf "$pack/payload.tar.xz"
fi

echo "== machine"
nvidia-smi -L 2>&1 | head -3
nproc

echo "== OpenCL driver"
# NVIDIA ships its OpenCL implementation as libnvidia-opencl.so.1; the carried ICD loader finds it
# through a vendors folder of our own.
driver=$(find /usr/local/nvidia /usr/lib /usr/lib64 /usr/lib/x86_64-linux-gnu -name 'libnvidia-opencl.so.1' 2>/dev/null | head -1)
[ -n "$driver" ] || driver=$(find / -xdev -name 'libnvidia-opencl.so*' 2>/dev/null | head -1)
echo "driver: ${driver:-none found}"
ls /etc/OpenCL/vendors 2>/dev/null
if [ -n "$driver" ]; then
  mkdir -p /tmp/ocl_vendors && echo "$driver" >/tmp/ocl_vendors/nvidia.icd
  export OCL_ICD_VENDORS=/tmp/ocl_vendors
fi
export LD_LIBRARY_PATH=$pack/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
ldconfig -p | grep -q 'libz.so.1 ' || export LD_LIBRARY_PATH=$LD_LIBRARY_PATH:$pack/libz

# The binaries carry the packing checkout's paths (its data and build folders); point them here.
home=$(cat "$pack/checkout_path" 2>/dev/null || echo /work/main)
if [ ! -e "$home/data/exemplars" ]; then mkdir -p "$(dirname "$home")" && ln -sfn "$root" "$home"; fi
build=$(cat "$pack/build_path" 2>/dev/null || echo "$home/build")
mkdir -p "$build/pocl_cache" "$build/test_tmp"
export TERRASYNTH_DATA_DIR=$root/data TERRASYNTH_BIN_DIR=$pack/bin TERRASYNTH_TEST_TMP=$build/test_tmp
export TERRASYNTH_SHARED_EXEMPLARS=$pack/shared_exemplars
export POCL_CACHE_DIR=$build/pocl_cache

echo "== devices seen by terrasynth"
# A device name that matches none makes the runtime list every device it can see.
TERRASYNTH_OPENCL_DEVICE='(list)' "$pack/bin/terrasynth" synth "$root/data/default.tsyn" --size 64x64 -o /tmp/list.png 2>&1 |
  grep -o 'available:.*'

echo "== OpenCL tests"
# At most 8 files come back from $OUT: the per-test logs travel as one archive.
tests_dir=/tmp/device_tests
mkdir -p "$tests_dir"
run_test() {
  local name=$1
  timeout 240 "$pack/tests/$name" --gtest_color=no --gtest_output="xml:$tests_dir/$name.xml" >"$tests_dir/$name.log" 2>&1
  local rc=$?
  echo "$name: exit $rc, $(grep -c '^\[       OK' "$tests_dir/$name.log") ok, $(grep -c '^\[  FAILED  \].*(' "$tests_dir/$name.log") failed"
  grep -E '^\[  FAILED  \]|worst|differing|Failure' "$tests_dir/$name.log" | head -8
  echo $rc >"$tests_dir/$name.rc"
}
[ -n "${DEVICE_CHECK_SKIP_TESTS:-}" ] || run_test cl_synthesis_test  # builds the default database that the others load
[ -n "${DEVICE_CHECK_SKIP_TESTS:-}" ] ||
for t in cl_coherence_test cl_drainage_internal_test cl_hardening_test cl_incremental_test project_session_test \
         project_constraints_test; do
  run_test $t &
done
wait
tar -C /tmp -czf "$OUT/tests.tar.gz" device_tests

echo "== synth_bench"
timeout 240 "$pack/bin/synth_bench" --benchmark_filter='OpenCL|LiftPoints' --benchmark_repetitions=5 \
  --benchmark_report_aggregates_only=true --benchmark_out="$OUT/synth_bench.json" --benchmark_out_format=json 2>&1 |
  grep -E 'median|Run on|CPU|Mpixel' | grep -v -E 'mean|stddev|cv'

echo "== drainage: breach over off on the device (BM_BreachOverOff: alternating pairs, medians)"
# The drainage's cost is breach_ms - off_ms: its kernels (kernels/drainage.cl) and the margins'
# extra correction work; the goal is at most the synthesis itself (off_ms). TERRASYNTH_CL_BREACH=host
# runs the host's search on the mapped state instead, for comparison.
for where in device host; do
  TERRASYNTH_CL_BREACH=$where timeout 240 "$pack/bin/synth_bench" --benchmark_filter='BreachOverOff' 2>&1 |
    awk -v w=$where '
      function value(s) {  # a counter as printed: 12.3, 1.23k
        sub(/^[a-z_]+=/, "", s)
        if (s ~ /k$/) return substr(s, 1, length(s) - 1) * 1000
        return s + 0
      }
      /^BM_BreachOverOff/ {
        for (i = 2; i <= NF; ++i) {
          if ($i ~ /^off_ms=/) off = value($i)
          if ($i ~ /^breach_ms=/) breach = value($i)
          if ($i ~ /^breach_over_off=/) ratio = value($i)
        }
        if (off > 0)
          printf "%s %s: synthesis (off) %.2f ms, breach %.2f ms, drainage %.2f ms = %.2f of the synthesis (pairs: %.3f)\n",
                 w, $1, off, breach, breach - off, (breach - off) / off, ratio
        else print w, $0  # an error instead of counters
      }'
done

if [ -x "$pack/bin/synth_bench_before" ]; then
  echo "== before | now, 1024^2, three interleaved rounds (median of 5 each)"
  for round in 1 2 3; do
    for b in synth_bench_before synth_bench; do
      printf '%s %s: ' "$round" "$b"
      timeout 120 "$pack/bin/$b" --benchmark_filter='BM_SynthesizeOpenCL[A-Za-z]*/1024' --benchmark_repetitions=5 \
        --benchmark_report_aggregates_only=true 2>&1 | awk '/median/{printf "%s %s %s  ", $1, $2, $3} END{print ""}'
    done
  done
fi

echo "== work-group shapes, 1024^2"
for shape in 32,2 16,16 64,4 128,1; do
  printf '%s: ' "$shape"
  TERRASYNTH_CL_LOCAL_SIZE=$shape timeout 60 "$pack/bin/synth_bench" --benchmark_filter='BM_SynthesizeOpenCL/1024' \
    --benchmark_repetitions=5 --benchmark_report_aggregates_only=true 2>&1 | grep median | awk '{print $2, $3}'
done

echo "== editing through the session and incremental synthesis (1024^2)"
timeout 150 "$pack/bin/session_bench" --benchmark_filter='PointDrag|UndoDragStep|Previewed' --benchmark_repetitions=3 \
  --benchmark_report_aggregates_only=true 2>&1 | grep median | awk '{print $1, $2, $3}'
timeout 100 "$pack/bin/incremental_bench" --benchmark_repetitions=3 --benchmark_report_aggregates_only=true 2>&1 |
  awk '$1 ~ /median$/ {print $1, $2, $3}'

echo "== larger extents (CLI, default project, drainage off and breach; synthesis time as printed)"
for size in 2048 4096 8192; do
  for drainage in off breach off breach; do
    timeout 120 "$pack/bin/terrasynth" synth "$root/data/default.tsyn" --size ${size}x$size --seed 3 --drainage $drainage \
      -o /tmp/big.f32 2>&1 | grep -o 'synthesis.*' | sed "s/^/${size}^2 $drainage: /"
  done
done

echo "== default project, 1024^2, seed 3, as float32 (compared bit for bit with PoCL here)"
# Here: terrasynth synth data/default.tsyn -o cpu.f32 --seed 3 [--drainage off], then cmp.
( cd "$root/data" && "$pack/bin/terrasynth" synth default.tsyn -o "$OUT/gpu_default.f32" --seed 3 &&
  "$pack/bin/terrasynth" synth default.tsyn -o "$OUT/gpu_default_off.f32" --seed 3 --drainage off ) 2>&1 | tail -4
echo "== done; test binaries that failed: $(grep -L -x 0 "$tests_dir"/*.rc 2>/dev/null | xargs -r -n1 basename | tr '\n' ' ')"
}

main 2>&1 | tee "$OUT/device_check.log"
