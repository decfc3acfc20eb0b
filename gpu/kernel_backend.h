#pragma once
// What every kernel-backed algorithm says of its backend: "cuda" runs the kernels on a device,
// "cuda-emu" runs the same kernel source under the CUDA-subset emulator (gpu/emulator). Each
// algorithm's backend struct adds its kernel entry points.
#include <optional>
#include <string>
#include <utility>

#include "shadowcts/variant_table_algorithm.h"

namespace shadowcts {

struct KernelBackend {
  std::string backend;  // "cuda" or "cuda-emu"
  std::string summary;
  // Why the kernels cannot run here (no device), or nullopt; nullptr: they always can.
  std::optional<std::string> (*unavailable_reason)() = nullptr;
  // AlgorithmInfo::emulated; adds the `emulated_threads` counter to every record.
  bool emulated = false;

  AlgorithmDescription describe(std::string id, const Capabilities& capabilities) const {
    return {.id = std::move(id),
            .backend = backend,
            .summary = summary,
            .capabilities = capabilities,
            .unavailable_reason = unavailable_reason,
            .emulated = emulated};
  }
};

}  // namespace shadowcts
