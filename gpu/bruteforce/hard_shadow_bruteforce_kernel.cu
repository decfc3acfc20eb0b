// The brute-force kernel (hard_shadow_bruteforce_kernel.cuh) built by nvcc for the device.
#include "gpu/bruteforce/hard_shadow_bruteforce_kernel.cuh"

#include <utility>

namespace shadowcts {

BruteforceShadowResult run_bruteforce_hard_shadow_kernel(BruteforceShadowInput input) {
  return device::bruteforce::run(std::move(input));
}

}  // namespace shadowcts
