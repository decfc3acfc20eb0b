// The lightassign kernels (lightassign_kernels.cuh) built by the host compiler against the
// CUDA-subset emulator.
#include "gpu/lightassign/lightassign_kernels.cuh"

#include <utility>

namespace shadowcts {

LightAssignKernelResult run_lightassign_kernels_emulated(LightAssignKernelInput input) {
  return emulated::lightassign::run(std::move(input));
}

}  // namespace shadowcts
