// The metric traversal kernel (traversal.cuh) built by nvcc for the device.
#include "gpu/metric/traversal.cuh"

#include <utility>

namespace shadowcts::gpu_metric {

MetricResult run_metric_traversal_kernel(MetricInput input) {
  return device::metric::run(std::move(input));
}

}  // namespace shadowcts::gpu_metric
