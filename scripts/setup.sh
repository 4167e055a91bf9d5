#!/usr/bin/env bash
# Installs every build and test dependency from Debian bookworm's packages (run as root, or with
# sudo available). Idempotent: does nothing when everything is already installed. slurm-wlm and
# munge serve the sharded-bake test, which starts its own throwaway cluster (scripts/slurm-local.sh).
set -euo pipefail
packages=(
  build-essential cmake pkg-config git
  pocl-opencl-icd ocl-icd-opencl-dev opencl-c-headers opencl-clhpp-headers clinfo
  libopenscenegraph-dev openscenegraph libglfw3-dev libglm-dev libimgui-dev
  libtinygltf-dev libmeshoptimizer-dev libpng-dev nlohmann-json3-dev libcli11-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  xvfb xauth libgl1-mesa-dri
  python3-numpy
  # The realism instrument in ../shared/realism (scripts/realism_survey.py, closeup_sheet.py,
  # hillshade_pairs.py): its gate needs scipy, its discriminator scikit-learn.
  python3-scipy python3-sklearn
  slurm-wlm munge
  # Hardening (issue 20): libFuzzer (clang and its runtime, scripts/fuzz.sh), valgrind
  # (scripts/valgrind_databases.sh), PIL for regenerating fuzz seeds (tests/fuzz/make_seeds.py).
  clang libclang-rt-14-dev valgrind python3-pil
  # Real DEMs (GDAL reads GeoTIFF, .hgt, .asc, .vrt; the build requires it; its tools make the
  # tests' GeoTIFFs), and the clients the export tests open files with: Blender's glTF importer
  # (headless) and Chromium for the CesiumJS view of a baked world (scripts/view_world.sh).
  libgdal-dev gdal-bin blender chromium
)
# The glTF validator runs on Node.js; machines that already have node/npm (e.g. from NodeSource)
# keep theirs, since Debian's npm package conflicts with it.
command -v npm >/dev/null 2>&1 || packages+=(nodejs npm)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
