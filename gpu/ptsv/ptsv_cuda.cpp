#include "gpu/ptsv/ptsv_cuda.h"

#include "gpu/device.h"
#include "gpu/ptsv/ptsv_algorithm.h"

namespace shadowcts {

std::unique_ptr<Algorithm> make_cuda_ptsv() {
  PtsvKernelBackend backend;
  backend.backend = "cuda";
  backend.summary =
      "per-triangle shadow volumes through the view-sample cluster hierarchy (Sintorn 2014) on the "
      "GPU: keys and hierarchy by Thrust sort and kernels, one warp per (node, volume) job with "
      "__ballot_sync over 32 children, atomicOr shadow bits; the reference's keys, nodes, "
      "counters and mask";
  backend.run_kernels = gpu_ptsv::run_ptsv_kernels;
  backend.unavailable_reason = cuda_unavailable_reason;
  return make_ptsv_kernel_algorithm(std::move(backend));
}

}  // namespace shadowcts
