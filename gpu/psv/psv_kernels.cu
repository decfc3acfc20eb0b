// The psv kernels (top_tree_build.cuh, psv_shadows.cuh) built by nvcc for the device.
#include "gpu/psv/psv_shadows.cuh"
#include "gpu/psv/top_tree_build.cuh"

#include <utility>

namespace shadowcts {

PsvQueryResult run_psv_query_kernel(PsvQueryInput input) {
  return device::psv::run(std::move(input));
}

std::unique_ptr<PsvDescentSession> make_psv_descent_session(const PsvDescentSetup& setup) {
  return std::make_unique<device::psv::DescentSession>(setup);
}

}  // namespace shadowcts
