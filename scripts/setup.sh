#!/usr/bin/env bash
# Installs terrasynth's Debian bookworm packages for one profile (run as root, or with sudo there).
# Idempotent: installs only what is missing, and nothing when all is there.
#
#   bash scripts/setup.sh [demo|test]          install a profile (default: test)
#   bash scripts/setup.sh --print [demo|test]  print its packages, one per line, install nothing
#
# demo: what building terrasynth without its tests (scripts/build.sh demo) and running its main job
#       (scripts/demo.sh) needs: the compiler, the libraries every REQUIRED find_package of that
#       build names, and PoCL, the OpenCL device the synthesis runs on.
# test: demo and everything the whole test suite (scripts/test.sh, CI) builds with and opens: the
#       test and benchmark frameworks, Xvfb and Mesa for the
#       windows, GDAL's tools, Python for the realism scripts and the Python module, clang and
#       valgrind for the hardening scripts, a throwaway Slurm cluster, Blender and Chromium, and
#       Node.js for the glTF validator and the CesiumJS client (test.sh runs `npm ci`).
set -euo pipefail

demo_packages=(
  build-essential cmake pkg-config
  # OpenCL: the ICD loader and headers to build against, PoCL to run on (CPU; a GPU's driver is
  # used instead when installed).
  pocl-opencl-icd ocl-icd-opencl-dev opencl-c-headers
  libpng-dev nlohmann-json3-dev libcli11-dev libtinygltf-dev libmeshoptimizer-dev
  # Real DEMs: GDAL reads GeoTIFF, .hgt, .asc, .vrt (the build requires it).
  libgdal-dev
  # The plugin, the window host, the editor and the game (OpenGL comes with GLFW's package).
  libopenscenegraph-dev libglfw3-dev libimgui-dev
)
test_packages=(
  "${demo_packages[@]}"
  libgtest-dev libgmock-dev libbenchmark-dev
  git opencl-clhpp-headers clinfo
  # osgviewer/osgconv (the README's plugin commands), windows without a display, GL in software.
  openscenegraph xvfb xauth libgl1-mesa-dri
  # GDAL's tools make the tests' GeoTIFFs.
  gdal-bin
  python3-numpy
  # The realism instrument in ../shared/realism (scripts/realism/realism_survey.py, closeup_sheet.py,
  # hillshade_pairs.py): its gate needs scipy, its discriminator scikit-learn.
  python3-scipy python3-sklearn
  # The soak scripts' plots (scripts/soak_game.sh).
  python3-matplotlib
  # The Python module (python/) and its pytest suite.
  python3-pybind11 python3-dev python3-pytest
  # The sharded-bake test starts its own throwaway cluster (scripts/slurm-local.sh).
  slurm-wlm munge
  # Hardening (issue 20): libFuzzer (clang and its runtime, scripts/fuzz.sh), valgrind
  # (scripts/valgrind_databases.sh), PIL for regenerating fuzz seeds (tests/fuzz/make_seeds.py).
  clang libclang-rt-14-dev valgrind python3-pil
  # The clients the export tests open files with: Blender's glTF importer (headless) and Chromium
  # for the CesiumJS view of a baked world (scripts/view_world.sh).
  blender chromium
)

print=false
if [ "${1:-}" = --print ]; then
  print=true
  shift
fi
profile="${1:-test}"
case "$profile" in
  demo) packages=("${demo_packages[@]}") ;;
  test)
    packages=("${test_packages[@]}")
    # The glTF validator runs on Node.js; machines that already have node/npm (e.g. from
    # NodeSource) keep theirs, since Debian's npm package conflicts with it.
    if $print || ! command -v npm >/dev/null 2>&1; then packages+=(nodejs npm); fi
    ;;
  *)
    echo "setup: unknown profile '$profile' (expected demo or test)" >&2
    echo "usage: bash scripts/setup.sh [--print] [demo|test]" >&2
    exit 2
    ;;
esac

if $print; then
  printf '%s\n' "${packages[@]}"
  exit 0
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup ($profile): installing ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
