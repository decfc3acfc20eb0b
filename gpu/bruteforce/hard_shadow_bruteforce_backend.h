#pragma once
// The Algorithm around the brute-force kernel, one for each build of the kernel source: the
// device (`cuda`) and the emulator (`cuda-emu`). Both finish the kernel's answer on the host the
// same way: samples the kernel leaves unsure (near a triangle edge or the light) are decided by the
// exact predicate, and a point light on a caster triangle shadows every sample it does not receive.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gpu/bruteforce/hard_shadow_bruteforce_kernel.h"
#include "gpu/kernel_backend.h"
#include "shadowcts/algorithm.h"
#include "shadowcts/case.h"
#include "shadowcts/view_samples.h"

namespace shadowcts {

struct BruteforceKernelBackend : KernelBackend {
  std::uint64_t max_sample_triangle_pairs = 0;
  BruteforceShadowResult (*run_kernel)(BruteforceShadowInput) = nullptr;
};

std::unique_ptr<Algorithm> make_bruteforce_kernel_algorithm(BruteforceKernelBackend backend);

// The kernel's input: regular samples (their indices appended to regular_samples) and caster
// triangles.
BruteforceShadowInput bruteforce_kernel_input(const Case& c, const ViewSamples& samples,
                                              std::vector<std::size_t>& regular_samples);

}  // namespace shadowcts
