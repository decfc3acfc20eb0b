#include "gpu/bruteforce/hard_shadow_bruteforce_cuda.h"

#include "gpu/bruteforce/hard_shadow_bruteforce_backend.h"
#include "gpu/bruteforce/hard_shadow_bruteforce_kernel.h"
#include "gpu/device.h"

namespace shadowcts {

std::unique_ptr<Algorithm> make_bruteforce_hard_shadow_cuda() {
  BruteforceKernelBackend backend;
  backend.backend = "cuda";
  backend.summary =
      "every regular sample against every caster triangle on the GPU, one thread per sample, "
      "watertight float32 segment/triangle test, exact host decision beside edges";
  // A few seconds on a current data-centre GPU.
  backend.max_sample_triangle_pairs = 40'000'000'000ull;
  backend.run_kernel = run_bruteforce_hard_shadow_kernel;
  backend.unavailable_reason = cuda_unavailable_reason;
  return make_bruteforce_kernel_algorithm(std::move(backend));
}

}  // namespace shadowcts
