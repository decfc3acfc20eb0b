// The lightassign kernels (lightassign_kernels.cuh) built by nvcc for the device.
#include "gpu/lightassign/lightassign_kernels.cuh"

namespace shadowcts {

LightAssignKernelResult run_lightassign_kernels(const LightAssignKernelInput& input) {
  return device::lightassign::run(input);
}

}  // namespace shadowcts
