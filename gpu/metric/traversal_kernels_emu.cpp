// The metric traversal kernel (traversal.cuh) built by the host compiler against the CUDA-subset
// emulator.
#include "gpu/metric/traversal.cuh"

namespace shadowcts::gpu_metric {

MetricResult run_metric_traversal_kernel_emulated(const MetricInput& input) {
  return emulated::metric::run(input);
}

}  // namespace shadowcts::gpu_metric
