// The psv query kernel (psv_shadows.cuh) built by nvcc for the device.
#include "gpu/psv/psv_shadows.cuh"

namespace shadowcts {

PsvQueryResult run_psv_query_kernel(const PsvQueryInput& input) {
  return device::psv::run(input);
}

}  // namespace shadowcts
