#pragma once
// The Algorithm around the psv query kernel, one for each build of the kernel source: the device
// (`cuda`) and the emulator (`cuda-emu`).
#include <memory>
#include <optional>
#include <string>

#include "gpu/psv/psv_shadows.h"
#include "shadowcts/algorithm.h"

namespace shadowcts::gpu_psv {

struct PsvKernelBackend {
  std::string backend;  // "cuda" or "cuda-emu"
  std::string summary;
  QueryKernel run_kernel = nullptr;
  DescentSessionMaker make_descent_session = nullptr;
  // Why the kernel cannot run here (no device), or nullopt; nullptr: it always can.
  std::optional<std::string> (*unavailable_reason)() = nullptr;
  bool emulated =
      false;  // AlgorithmInfo::emulated; adds the `emulated_threads` counter to every record
};

std::unique_ptr<Algorithm> make_psv_kernel_algorithm(PsvKernelBackend backend);

// Threads per block of the query kernel (psv_shadows.cuh), for the emulated_threads counter.
inline constexpr std::uint64_t psv_threads_per_block = 128;

}  // namespace shadowcts::gpu_psv
