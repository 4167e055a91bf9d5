#!/usr/bin/env bash
# Fills .device/ (.gitignore) with what scripts/device_check.sh runs on a lent GPU machine:
# the built OpenCL tests, synth_bench and the CLI, and the non-system shared libraries they load
# (that machine runs another distribution and has no package registry), packed into one archive.
#   COMPARE_WITH=/path/to/older/synth_bench bash scripts/device_pack.sh   (optional)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD_DIR:-build}
cmake --build "$build" -j2 --target synth_bench session_bench incremental_bench terrasynth_cli cl_synthesis_test cl_coherence_test \
  cl_drainage_internal_test cl_hardening_test cl_incremental_test project_session_test project_constraints_test >/dev/null
rm -rf .device && mkdir -p .device/bin .device/tests .device/lib .device/libz
cp "$build"/bin/synth_bench "$build"/bin/session_bench "$build"/bin/incremental_bench "$build"/bin/terrasynth .device/bin/
# An earlier build's synth_bench to compare with in the same run: COMPARE_WITH=path/to/synth_bench.
[ -z "${COMPARE_WITH:-}" ] || cp "$COMPARE_WITH" .device/bin/synth_bench_before
for t in cl_synthesis_test cl_coherence_test cl_drainage_internal_test cl_hardening_test cl_incremental_test \
         project_session_test project_constraints_test; do cp "$build/tests/$t" .device/tests/; done
# The shared DEMs cl_drainage_internal_test synthesizes (the machine has no ../shared).
mkdir -p .device/shared_exemplars
cp "${TERRASYNTH_SHARED_EXEMPLARS:-../shared/exemplars}"/{orom_gobi,ttb_bigtujunga}.{png,json} .device/shared_exemplars/
# Every shared library outside glibc and the compiler runtime; zlib apart, used only where missing.
ldd .device/bin/* .device/tests/* | awk '/=> \//{print $3}' | sort -u |
  grep -v -E '/(libc|libm|libgcc_s|libstdc\+\+|ld-linux[^/]*)\.so' | while read -r lib; do
    case $lib in */libz.so.*) cp -L "$lib" .device/libz/ ;; *) cp -L "$lib" .device/lib/ ;; esac
  done
# The binaries carry this checkout's absolute paths (data, build); device_check.sh links them there.
pwd >.device/checkout_path
(cd "$build" && pwd) >.device/build_path
# GDAL's dependencies alone come to ~150 MB and the device tool carries at most 64 MiB with the
# checkout: binaries and libraries travel as one xz archive (~50 MB), which device_check.sh unpacks.
tar -C .device -cf - bin tests lib libz | xz -T2 -6 >.device/payload.tar.xz
rm -rf .device/bin .device/tests .device/lib .device/libz
du -sh .device
