// The CUDA ptsv kernels (ptsv_kernels.cuh) built by nvcc for the device.
#include "gpu/ptsv/ptsv_kernels.cuh"

#include <utility>

namespace shadowcts::gpu_ptsv {

KernelResult run_ptsv_kernels(KernelInput input) {
  return device::ptsv::run(std::move(input));
}

}  // namespace shadowcts::gpu_ptsv
