// The device backend (`cuda`), built only with CUDA (shadowcts_gpu).
#include "gpu/device.h"
#include "gpu/psv/psv_algorithm.h"
#include "gpu/psv/psv_backend.h"
#include "gpu/psv/psv_kernels.h"

namespace shadowcts {

std::unique_ptr<Algorithm> make_psv_cuda() {
  gpu_psv::PsvKernelBackend backend;
  backend.backend = "cuda";
  backend.summary =
      "partitioned shadow volumes on the GPU: the TOP tree's descents in batches on the device, "
      "committed on the host (the reference's tree, node for node), one thread per sample with "
      "the exact plane sides; PSV, D-PSV, D-Stackless, D-Hybrid (Mora 2016)";
  backend.run_kernel = run_psv_query_kernel;
  backend.make_descent_session = make_psv_descent_session;
  backend.unavailable_reason = cuda_unavailable_reason;
  return gpu_psv::make_psv_kernel_algorithm(std::move(backend));
}

}  // namespace shadowcts
