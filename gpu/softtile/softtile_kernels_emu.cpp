// The softtile kernels (softtile_tile.cuh) built by the host compiler against the CUDA-subset
// emulator.
#include "gpu/softtile/softtile_tile.cuh"

namespace shadowcts {

SofttileKernelResult run_softtile_kernel_emulated(const SofttileKernelInput& input) {
  return emulated::softtile::run(input);
}

}  // namespace shadowcts
