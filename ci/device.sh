#!/usr/bin/env bash
# What a machine with a GPU runs, in one command: the device tests, the conformance cases of every
# `cuda` backend, and the device and emulated builds of every kernel on the same cases compared
# sample by sample (robust samples must agree; every difference is listed with its ambiguity
# class), ending with that table. Exits 3 where no CUDA device can be used.
#
# Two ways to get the programs:
# - built here (a few minutes on a 16-core machine): ci/setup.sh installs what is missing and
#   builds the CUDA backend with nvcc beside the emulated one. Needs Debian's packages.
# - from a bundle that ci/device_bundle.sh wrote on another machine (programs, their shared
#   libraries and the model fixtures): for a GPU machine with a driver but without the packages
#   or a network. Used when SHADOWCTS_DEVICE_BUNDLE names it or .device-bundle.tar.xz exists.
#
#   SHADOWCTS_BUILD_DIR      build folder when building here (default: build-device)
#   SHADOWCTS_DEVICE_BUNDLE  the bundle to run instead of building
#   SHADOWCTS_DEVICE_TIMING  a folder: also time cuda against simd, reference and Embree at
#                            1920 x 1080 (`shadowcts run`, sampled oracles, no images) and write
#                            each case's results.json and log there
set -uo pipefail
cd "$(dirname "$0")/.." || exit 1

source ci/device_programs.sh
declare -A path_in_build=()
for p in "${device_programs[@]}"; do path_in_build[$(basename "$p")]="$p"; done

scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
bundle="${SHADOWCTS_DEVICE_BUNDLE:-}"
[ -z "$bundle" ] && [ -f .device-bundle.tar.xz ] && bundle=.device-bundle.tar.xz
if [ -n "$bundle" ]; then
  [ -f "$bundle" ] || { echo "device: no bundle at $bundle" >&2; exit 2; }
  # xz, or Python's lzma where the machine has no xz (an image built for Python work).
  unxz() {
    if command -v xz >/dev/null; then
      xz -dc "$1"
    else
      python3 -c 'import lzma, shutil, sys; shutil.copyfileobj(lzma.open(sys.argv[1]), sys.stdout.buffer)' "$1"
    fi
  }
  unxz "$bundle" | tar -C "$scratch" -xf - || { echo "device: cannot unpack $bundle" >&2; exit 2; }
  root="$scratch/shadowcts-device"
  loader="$(ls "$root"/lib/ld-linux-x86-64.so.* 2>/dev/null | head -n 1)"
  [ -n "$loader" ] || { echo "device: $bundle holds no dynamic loader" >&2; exit 2; }
  echo "device: programs of commit $(paste -sd' ' "$root/commit") from $bundle"
  # The carried libraries hold all of glibc; the machine gives only its driver (libcuda), found
  # after them.
  driver_dirs="$(ldconfig -p 2>/dev/null | awk '/libcuda\.so\.1 / { print $NF }' |
    xargs -r -n 1 dirname | sort -u | paste -sd:)"
  library_path="$root/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}:/usr/local/nvidia/lib64"
  library_path+=":/usr/lib/x86_64-linux-gnu${driver_dirs:+:$driver_dirs}"
  export SHADOWCTS_ASSIMP_MODELS="$root/models"
  program() {
    local name="$1"
    shift
    "$loader" --library-path "$library_path" "$root/bin/$name" "$@"
  }
else
  [ -x /usr/local/cuda/bin/nvcc ] && export PATH="/usr/local/cuda/bin:$PATH"
  if ! command -v nvcc >/dev/null; then
    echo "device: no nvcc on this machine (the CUDA toolkit is not installed) and no bundle" >&2
    exit 2
  fi
  export SHADOWCTS_BUILD_DIR="${SHADOWCTS_BUILD_DIR:-build-device}"
  SHADOWCTS_TARGETS="${!path_in_build[*]}" bash ci/setup.sh || exit 1
  program() {
    local name="$1"
    shift
    "$SHADOWCTS_BUILD_DIR/${path_in_build[$name]}" "$@"
  }
fi

status=0
probe="$scratch/probe.log"
program hard_shadow_bruteforce_cuda_test 2>&1 | tee "$probe"
[ "${PIPESTATUS[0]}" -eq 0 ] || status=1
if grep -q "no CUDA device" "$probe"; then
  # Everything below would be skipped: say so and fail, a device check that checked nothing.
  echo "device: $(grep -m 1 -o "no CUDA device.*" "$probe"): nothing to check on this machine" >&2
  exit 3
fi
program gpu_metric_cuda_test --gtest_brief=1 || status=1
program conformance_test --gtest_filter='*_cuda_*:-*_cuda_emu_*' --gtest_brief=1 || status=1
program device_emulator_comparison_test || status=1

if [ -n "${SHADOWCTS_DEVICE_TIMING:-}" ]; then
  timing="$SHADOWCTS_DEVICE_TIMING"
  mkdir -p "$timing/cases" || exit 1
  # The timing cases of issues 18-22: fixture, triangles, algorithms, backends (the reference
  # only where one run of it takes seconds, not minutes).
  runs=(
    "gate_house 1000000 psv:stackless,embree cuda,simd,reference,embree"
    "ground_blockers 1000000 psv:stackless,embree cuda,simd,reference,embree"
    "closed_shapes 1000000 psv:stackless,embree cuda,simd,reference,embree"
    "foliage 100000 softtile:grid16,embree_soft:rays64 cuda,simd,reference,embree"
    "foliage 1000000 softtile:grid16,embree_soft:rays64 cuda,simd,embree"
    "gate_house 100000 ptsv:twopass,metric:capsules,embree cuda,simd,reference,embree"
    "many_lights 4000000 lightassign:clustered,lightassign:tiled cuda,simd,reference"
  )
  for r in "${runs[@]}"; do
    read -r generator triangles algorithms backends <<<"$r"
    name="$generator.$triangles"
    printf '{"scene": {"generator": "%s", "triangles": %s}, "camera": {"width": 1920, "height": 1080}}\n' \
      "$generator" "$triangles" > "$timing/cases/$name.json"
    arguments=()
    for a in ${algorithms//,/ }; do arguments+=(--algorithm "$a"); done
    for b in ${backends//,/ }; do arguments+=(--backend "$b"); done
    echo "device: timing $name ($algorithms on $backends)"
    program shadowcts run --case "$timing/cases/$name.json" "${arguments[@]}" --oracle embree \
      --repeat 3 --no-images --out "$timing/$name" > "$timing/$name.log" 2>&1 || status=1
    tail -n 3 "$timing/$name.log"
  done
fi
exit "$status"
