// The metric traversal kernel (traversal.cuh) built by the host compiler against the CUDA-subset
// emulator.
#include "gpu/metric/traversal.cuh"

#include <utility>

namespace shadowcts::gpu_metric {

MetricResult run_metric_traversal_kernel_emulated(MetricInput input) {
  return emulated::metric::run(std::move(input));
}

}  // namespace shadowcts::gpu_metric
