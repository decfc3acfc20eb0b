// The softtile kernels (softtile_tile.cuh) built by nvcc for the device.
#include "gpu/softtile/softtile_tile.cuh"

namespace shadowcts {

SofttileKernelResult run_softtile_kernel(const SofttileKernelInput& input) {
  return device::softtile::run(input);
}

}  // namespace shadowcts
