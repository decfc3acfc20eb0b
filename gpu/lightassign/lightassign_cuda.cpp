#include "gpu/lightassign/lightassign_cuda.h"

#include "gpu/device.h"
#include "gpu/lightassign/lightassign_algorithm.h"
#include "gpu/lightassign/lightassign_kernels.h"

namespace shadowcts {

std::unique_ptr<Algorithm> make_lightassign_cuda() {
  LightAssignKernelBackend backend;
  backend.backend = "cuda";
  backend.summary =
      "tiled and clustered light assignment on the GPU: cluster keys per sample, Thrust sort + "
      "unique, device-built 32-wide light BVH traversed by one warp per cluster, lists by count / "
      "scan / write; the reference's lists";
  backend.run_kernels = run_lightassign_kernels;
  backend.unavailable_reason = cuda_unavailable_reason;
  return make_lightassign_kernel_algorithm(std::move(backend));
}

}  // namespace shadowcts
