#pragma once
// The Algorithm around the lightassign kernels, one for each build of the kernel source: the
// device (`cuda`) and the emulator (`cuda-emu`). Variants, unsupported reasons and counters are
// the reference's (reference/lightassign/lightassign_algorithm.h); `brute` stays the reference's.
#include <memory>
#include <optional>
#include <string>

#include "gpu/kernel_backend.h"
#include "gpu/lightassign/lightassign_kernels.h"
#include "shadowcts/algorithm.h"
#include "shadowcts/prepared_scene.h"

namespace shadowcts {

struct LightAssignKernelBackend : KernelBackend {
  LightAssignKernelResult (*run_kernels)(LightAssignKernelInput) = nullptr;
};

std::unique_ptr<Algorithm> make_lightassign_kernel_algorithm(LightAssignKernelBackend backend);

// The kernels' input for one variant of the scene (throws std::invalid_argument for a variant
// the kernels do not implement). Its hooks refer to scene.source's camera.
LightAssignKernelInput lightassign_kernel_input(const PreparedScene& scene,
                                                const std::string& variant);

// id "lightassign", backend "cuda-emu": the kernels run by the CUDA-subset emulator; counters as
// the reference plus "emulated_threads".
std::unique_ptr<Algorithm> make_lightassign_cuda_emu();

}  // namespace shadowcts
