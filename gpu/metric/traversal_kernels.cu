// The metric traversal kernel (traversal.cuh) built by nvcc for the device.
#include "gpu/metric/traversal.cuh"

namespace shadowcts::gpu_metric {

MetricResult run_metric_traversal_kernel(const MetricInput& input) {
  return device::metric::run(input);
}

}  // namespace shadowcts::gpu_metric
