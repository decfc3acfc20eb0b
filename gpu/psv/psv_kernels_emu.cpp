// The psv kernels (top_tree_build.cuh, psv_shadows.cuh) built by the host compiler against the
// CUDA-subset emulator.
#include "gpu/psv/psv_shadows.cuh"
#include "gpu/psv/top_tree_build.cuh"

#include <utility>

namespace shadowcts {

PsvQueryResult run_psv_query_kernel_emulated(PsvQueryInput input) {
  return emulated::psv::run(std::move(input));
}

std::unique_ptr<PsvDescentSession> make_psv_descent_session_emulated(const PsvDescentSetup& setup) {
  return std::make_unique<emulated::psv::DescentSession>(setup);
}

}  // namespace shadowcts
