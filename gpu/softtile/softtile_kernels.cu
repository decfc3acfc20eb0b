// The softtile kernels (softtile_tile.cuh) built by nvcc for the device.
#include "gpu/softtile/softtile_tile.cuh"

#include <utility>

namespace shadowcts {

SofttileKernelResult run_softtile_kernel(SofttileKernelInput input) {
  return device::softtile::run(std::move(input));
}

}  // namespace shadowcts
