// The brute-force kernel (hard_shadow_bruteforce_kernel.cuh) built by the host compiler against
// the CUDA-subset emulator.
#include "gpu/bruteforce/hard_shadow_bruteforce_kernel.cuh"

namespace shadowcts {

BruteforceShadowResult run_bruteforce_hard_shadow_kernel_emulated(
    const BruteforceShadowInput& input) {
  return emulated::bruteforce::run(input);
}

}  // namespace shadowcts
