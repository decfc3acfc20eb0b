#include "gpu/softtile/softtile_cuda.h"

#include "gpu/device.h"
#include "gpu/softtile/softtile_algorithm.h"
#include "gpu/softtile/softtile_kernel.h"

namespace shadowcts {

std::unique_ptr<Algorithm> make_softtile_cuda() {
  SofttileKernelBackend backend;
  backend.backend = "cuda";
  backend.summary =
      "softtile on the GPU: a block per 16x16 tile culls cluster and triangle cones into a shared "
      "candidate list, a thread per pixel rasterizes its disk bitmask";
  backend.run_kernel = run_softtile_kernel;
  backend.unavailable_reason = cuda_unavailable_reason;
  return make_softtile_kernel_algorithm(std::move(backend));
}

}  // namespace shadowcts
