// The `cuda` backend of metric: the traversal kernel on the device (traversal_kernels.cu).
#include "gpu/device.h"
#include "gpu/metric/metric_algorithm.h"

namespace shadowcts {

std::unique_ptr<Algorithm> make_metric_cuda() {
  MetricKernelBackend backend;
  backend.backend = "cuda";
  backend.summary =
      "clustered metric-tree shadows on the GPU: the reference's clusters and ternary metric tree "
      "uploaded, one thread per sample walks it with a fixed stack and tests the candidate "
      "clusters' triangles watertight, exact beside edges (Deves 2018)";
  backend.run_kernel = gpu_metric::run_metric_traversal_kernel;
  backend.unavailable_reason = cuda_unavailable_reason;
  return make_metric_kernel_algorithm(std::move(backend));
}

}  // namespace shadowcts
