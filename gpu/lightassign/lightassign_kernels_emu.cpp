// The lightassign kernels (lightassign_kernels.cuh) built by the host compiler against the
// CUDA-subset emulator.
#include "gpu/lightassign/lightassign_kernels.cuh"

namespace shadowcts {

LightAssignKernelResult run_lightassign_kernels_emulated(const LightAssignKernelInput& input) {
  return emulated::lightassign::run(input);
}

}  // namespace shadowcts
