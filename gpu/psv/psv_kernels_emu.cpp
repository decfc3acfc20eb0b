// The psv query kernel (psv_shadows.cuh) built by the host compiler against the CUDA-subset
// emulator.
#include "gpu/psv/psv_shadows.cuh"

namespace shadowcts {

PsvQueryResult run_psv_query_kernel_emulated(const PsvQueryInput& input) {
  return emulated::psv::run(input);
}

}  // namespace shadowcts
