#!/usr/bin/env bash
# Sets up a fresh Debian 12 machine for shadowcts and builds it. Idempotent: installs only the
# packages that are missing, reconfigures and rebuilds incrementally.
#   SHADOWCTS_BUILD_DIR  build folder (default: build)
#   SHADOWCTS_JOBS       parallel build jobs (default: number of cores)
#   SHADOWCTS_TARGETS    space-separated targets to build (default: all)
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake pkg-config ccache clang-format
  libembree-dev libcgal-dev libgmp-dev libmpfr-dev libopenmesh-dev libopenimageio-dev
  libtinygltf-dev libglm-dev libhwy-dev libtbb-dev libgtest-dev libgmock-dev libbenchmark-dev
  nlohmann-json3-dev libcli11-dev assimp-testmodels chromium clang-14 libclang-rt-14-dev
  libboost-context-dev libthrust-dev libssl-dev
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

build_dir="${SHADOWCTS_BUILD_DIR:-build}"
jobs="${SHADOWCTS_JOBS:-$(nproc)}"
launcher=()
# Paths inside the checkout enter ccache's hashes relative to the build folder, so a clone at
# another path (CI's) reuses what any earlier build of the same sources compiled.
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$PWD}"
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_CUDA_COMPILER_LAUNCHER=ccache)
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release "${launcher[@]}"
targets=()
for t in ${SHADOWCTS_TARGETS:-}; do targets+=(--target "$t"); done
cmake --build "$build_dir" -j "$jobs" "${targets[@]}"
