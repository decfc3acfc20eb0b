#!/usr/bin/env bash
# What a machine with a GPU runs, in one command (a few minutes on a 16-core machine): installs
# what is missing and builds the CUDA backend with nvcc beside the emulated one (ci/setup.sh),
# then runs the device tests, the conformance cases of every `cuda` backend, and the device and
# emulated builds of every kernel on the same cases compared sample by sample (robust samples must
# agree; every difference is listed with its ambiguity class), ending with that table.
#   SHADOWCTS_BUILD_DIR  build folder (default: build-device)
set -uo pipefail
cd "$(dirname "$0")/.." || exit 1
[ -x /usr/local/cuda/bin/nvcc ] && export PATH="/usr/local/cuda/bin:$PATH"
if ! command -v nvcc >/dev/null; then
  echo "device: no nvcc on this machine (the CUDA toolkit is not installed)" >&2
  exit 2
fi
export SHADOWCTS_BUILD_DIR="${SHADOWCTS_BUILD_DIR:-build-device}"
SHADOWCTS_TARGETS="hard_shadow_bruteforce_cuda_test gpu_metric_cuda_test conformance_test device_emulator_comparison_test" \
  bash ci/setup.sh || exit 1
build="$SHADOWCTS_BUILD_DIR"
status=0
"$build/tests/gpu/hard_shadow_bruteforce_cuda_test" || status=1
"$build/tests/gpu/metric/gpu_metric_cuda_test" --gtest_brief=1 || status=1
"$build/tests/conformance/conformance_test" --gtest_filter='*_cuda_*:-*_cuda_emu_*' --gtest_brief=1 ||
  status=1
"$build/tests/gpu/device_emulator_comparison_test" || status=1
exit "$status"
