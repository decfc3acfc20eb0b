// The emulated backend (`cuda-emu`); the device one is in psv_algorithm_cuda.cpp (CUDA builds).
#include "gpu/psv/psv_algorithm.h"

#include "gpu/psv/psv_backend.h"
#include "gpu/psv/psv_kernels.h"

namespace shadowcts {

std::unique_ptr<Algorithm> make_psv_cuda_emu() {
  gpu_psv::PsvKernelBackend backend;
  backend.backend = "cuda-emu";
  backend.summary =
      "the cuda backend's psv kernels EMULATED on the host (gpu/emulator: a fiber per CUDA "
      "thread, no GPU involved): the TOP tree's descents in batches (the reference's tree, node "
      "for node), then PSV, D-PSV, D-Stackless, D-Hybrid";
  backend.run_kernel = run_psv_query_kernel_emulated;
  backend.make_descent_session = make_psv_descent_session_emulated;
  backend.emulated = true;
  return gpu_psv::make_psv_kernel_algorithm(std::move(backend));
}

}  // namespace shadowcts
