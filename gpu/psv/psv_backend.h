#pragma once
// The Algorithm around the psv query kernel, one for each build of the kernel source: the device
// (`cuda`) and the emulator (`cuda-emu`).
#include <memory>
#include <optional>
#include <string>

#include "gpu/kernel_backend.h"
#include "gpu/psv/psv_shadows.h"
#include "shadowcts/algorithm.h"

namespace shadowcts::gpu_psv {

struct PsvKernelBackend : KernelBackend {
  QueryKernel run_kernel = nullptr;
  DescentSessionMaker make_descent_session = nullptr;
};

std::unique_ptr<Algorithm> make_psv_kernel_algorithm(PsvKernelBackend backend);

// Threads per block of the query kernel (psv_shadows.cuh), for the emulated_threads counter.
inline constexpr std::uint64_t psv_threads_per_block = 128;

}  // namespace shadowcts::gpu_psv
