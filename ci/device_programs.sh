# The programs ci/device.sh runs, by their path in a build folder (ci/device_bundle.sh packs them;
# both source this file).
device_programs=(
  shadowcts
  tests/gpu/hard_shadow_bruteforce_cuda_test
  tests/gpu/metric/gpu_metric_cuda_test
  tests/conformance/conformance_test
  tests/gpu/device_emulator_comparison_test
)
