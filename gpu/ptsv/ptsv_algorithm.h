#pragma once
// CUDA `ptsv`: the reference's Sintorn 2014 per-triangle shadow volumes (reference/ptsv/) with the
// cluster keys, the hierarchy (a Thrust sort of the keys, 32-wide levels, explicit bounds reduced
// by kernels) and the traversal (one warp per (node, volume) job, __ballot_sync over the 32
// children, atomicOr into per-sample shadow bits) on the device; the shadow volumes and the
// receivers' half-spaces are set up on the host as the reference sets them up. Variants twopass,
// explicit+planes, implicit (the reference's names and configurations); the keys, the nodes, the
// counters and the mask are the reference's. Backends `cuda` (nvcc, NotSupported without a
// device) and `cuda-emu` (the same kernels on the CUDA-subset emulator).
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "gpu/kernel_backend.h"
#include "gpu/ptsv/ptsv_kernels.h"
#include "shadowcts/algorithm.h"
#include "shadowcts/prepared_scene.h"

namespace shadowcts {

struct PtsvKernelBackend : KernelBackend {
  gpu_ptsv::KernelResult (*run_kernels)(gpu_ptsv::KernelInput) = nullptr;
  // Capabilities::max_sample_triangle_pairs (0: no limit) and why, with the cost measured near
  // it: the NotSupported reason above it says both.
  std::uint64_t max_sample_triangle_pairs = 0;
  std::string size_limit_reason;
};

std::unique_ptr<Algorithm> make_ptsv_kernel_algorithm(PtsvKernelBackend backend);

// id "ptsv", backend "cuda-emu".
std::unique_ptr<Algorithm> make_cuda_emu_ptsv();

namespace gpu_ptsv {

// The kernels' input for a case the variant supports (the host's share: volumes, receivers'
// half-spaces, reject reaches, slice starts, tolerances). Throws InputError as the reference does.
KernelInput kernel_input(const PreparedScene& scene, const std::string& variant);

}  // namespace gpu_ptsv
}  // namespace shadowcts
