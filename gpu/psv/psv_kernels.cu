// The psv kernels (top_tree_build.cuh, psv_shadows.cuh) built by nvcc for the device.
#include "gpu/psv/psv_shadows.cuh"
#include "gpu/psv/top_tree_build.cuh"

namespace shadowcts {

PsvQueryResult run_psv_query_kernel(const PsvQueryInput& input) {
  return device::psv::run(input);
}

std::unique_ptr<PsvDescentSession> make_psv_descent_session(const PsvDescentSetup& setup) {
  return std::make_unique<device::psv::DescentSession>(setup);
}

}  // namespace shadowcts
