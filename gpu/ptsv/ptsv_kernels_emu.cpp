// The CUDA ptsv kernels (ptsv_kernels.cuh) built by the host compiler against the CUDA-subset
// emulator.
#include "gpu/ptsv/ptsv_kernels.cuh"

#include <utility>

namespace shadowcts::gpu_ptsv {

KernelResult run_ptsv_kernels_emulated(KernelInput input) {
  return emulated::ptsv::run(std::move(input));
}

}  // namespace shadowcts::gpu_ptsv
