#pragma once
// cuda / cuda-emu `softtile`: the reference's gather pass (reference/softtile/softtile_gather.h)
// and the per-pixel grid rotation (cos / sin of the seeded angle) on the host, then one kernel
// (softtile_tile.cuh) per frame: a block per 16 x 16 tile builds the tile's bound (sphere or
// tapered capsule), culls the cluster and triangle cones against it into its candidate list in
// shared memory, and every thread rasterizes the candidates into its pixel's disk bitmask. Same
// candidate lists, masks, answers and counters as the reference for every variant. One Algorithm
// for each build of the kernel source: the device (`cuda`) and the emulator (`cuda-emu`).
#include <memory>
#include <optional>
#include <string>

#include "gpu/kernel_backend.h"
#include "gpu/softtile/softtile_kernel.h"
#include "reference/softtile/softtile_gather.h"
#include "reference/softtile/softtile_variant.h"
#include "shadowcts/algorithm.h"
#include "shadowcts/case.h"
#include "shadowcts/view_samples.h"

namespace shadowcts {

struct SofttileKernelBackend : KernelBackend {
  SofttileKernelResult (*run_kernel)(SofttileKernelInput) = nullptr;
};

// id "softtile", the reference's budgets and counters; variants grid16, grid16+rot, rows15,
// rows31, post (issue 21's).
std::unique_ptr<Algorithm> make_softtile_kernel_algorithm(SofttileKernelBackend backend);

// Backend "cuda-emu": the kernel run by the CUDA-subset emulator; adds "emulated_threads".
std::unique_ptr<Algorithm> make_softtile_cuda_emu();

// The kernel's input: the gathered clusters and triangles, the variant's disk, the camera and
// light space, and per pixel the sample, its grid rotation and its receiver.
SofttileKernelInput softtile_kernel_input(const Case& c, const ViewSamples& samples,
                                          const softtile::Variant& variant,
                                          const softtile::Gathered& gathered);

}  // namespace shadowcts
