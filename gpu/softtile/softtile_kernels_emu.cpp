// The softtile kernels (softtile_tile.cuh) built by the host compiler against the CUDA-subset
// emulator.
#include "gpu/softtile/softtile_tile.cuh"

#include <utility>

namespace shadowcts {

SofttileKernelResult run_softtile_kernel_emulated(SofttileKernelInput input) {
  return emulated::softtile::run(std::move(input));
}

}  // namespace shadowcts
