#include "gpu/bruteforce/hard_shadow_bruteforce_emu.h"

#include "gpu/bruteforce/hard_shadow_bruteforce_backend.h"
#include "gpu/bruteforce/hard_shadow_bruteforce_kernel.h"

namespace shadowcts {

std::unique_ptr<Algorithm> make_bruteforce_hard_shadow_cuda_emu() {
  BruteforceKernelBackend backend;
  backend.backend = "cuda-emu";
  backend.summary =
      "the cuda backend's brute-force kernel EMULATED on the host (gpu/emulator: a fiber per "
      "CUDA thread, no GPU involved), exact host decision beside edges";
  // The reference brute force's limit, so both run on the same cases. About 40 ns per pair on
  // one core (model.spider, 85M pairs: 4.2 s against the reference's 0.76 s), so the largest
  // case takes ~6 s on two cores per run.
  backend.max_sample_triangle_pairs = 300'000'000ull;
  backend.run_kernel = run_bruteforce_hard_shadow_kernel_emulated;
  backend.emulated = true;
  return make_bruteforce_kernel_algorithm(std::move(backend));
}

}  // namespace shadowcts
