// The CUDA ptsv kernels (ptsv_kernels.cuh) built by nvcc for the device.
#include "gpu/ptsv/ptsv_kernels.cuh"

namespace shadowcts::gpu_ptsv {

KernelResult run_ptsv_kernels(const KernelInput& input) {
  return device::ptsv::run(input);
}

}  // namespace shadowcts::gpu_ptsv
