// The lightassign kernels (lightassign_kernels.cuh) built by nvcc for the device.
#include "gpu/lightassign/lightassign_kernels.cuh"

#include <utility>

namespace shadowcts {

LightAssignKernelResult run_lightassign_kernels(LightAssignKernelInput input) {
  return device::lightassign::run(std::move(input));
}

}  // namespace shadowcts
