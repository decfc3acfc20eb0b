#pragma once
// Device allocations and transfers of the lightassign kernels, for both builds (gpu/emulator/
// kernel.h maps the runtime calls onto the emulator's host memory).
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "gpu/device_array.cuh"
#include "gpu/emulator/kernel.h"
#if SHADOWCTS_EMULATED
#include <bit>
#endif

namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE::lightassign {

// Four warps per block for the per-item kernels; the warp-per-list kernels use the same.
constexpr int threads_per_block = 128;
constexpr unsigned full_warp = 0xffffffffu;
// warpSize for host code (CUDA's warpSize is a device variable).
constexpr unsigned lanes_per_warp = 32;

// Counts the threads of every launch (the emulated backend's `emulated_threads`) and checks it.
struct Launches {
  std::uint64_t threads = 0;
  unsigned blocks_for(std::size_t items, unsigned block) {
    const auto blocks = unsigned((items + block - 1) / block);
    threads += std::uint64_t(blocks) * block;
    return blocks;
  }
  static void finish(const char* kernel) {
    check(cudaGetLastError(), kernel);
    check(cudaDeviceSynchronize(), kernel);
  }
};

// Population count and the lanes below this one, in both builds.
__device__ inline unsigned bit_count(unsigned x) {
#if SHADOWCTS_EMULATED
  return unsigned(std::popcount(x));
#else
  return unsigned(__popc(x));
#endif
}

__device__ inline unsigned lanes_below(unsigned lane) {
  return (1u << lane) - 1u;
}

}  // namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE::lightassign
