// The brute-force kernel (hard_shadow_bruteforce_kernel.cuh) built by the host compiler against
// the CUDA-subset emulator.
#include "gpu/bruteforce/hard_shadow_bruteforce_kernel.cuh"

#include <utility>

namespace shadowcts {

BruteforceShadowResult run_bruteforce_hard_shadow_kernel_emulated(BruteforceShadowInput input) {
  return emulated::bruteforce::run(std::move(input));
}

}  // namespace shadowcts
