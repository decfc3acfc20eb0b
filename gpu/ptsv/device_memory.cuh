#pragma once
// Device allocations and copies of the CUDA ptsv (both builds: nvcc and the emulator).
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "gpu/device_array.cuh"
#include "gpu/emulator/kernel.h"

namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE::ptsv {

// Bits set in v (no intrinsic: the emulator has none).
__device__ inline std::uint32_t bit_count(std::uint32_t v) {
  v = v - ((v >> 1) & 0x55555555u);
  v = (v & 0x33333333u) + ((v >> 2) & 0x33333333u);
  return (((v + (v >> 4)) & 0x0F0F0F0Fu) * 0x01010101u) >> 24;
}

constexpr unsigned threads_per_block = 128;
constexpr unsigned warps_per_block = threads_per_block / 32;

inline unsigned blocks_for(std::size_t threads) {
  return static_cast<unsigned>((threads + threads_per_block - 1) / threads_per_block);
}

// Counts the threads of every launch (the `emulated_threads` counter of the cuda-emu records).
struct LaunchCount {
  std::uint64_t threads = 0;
  unsigned blocks(std::size_t wanted_threads) {
    const unsigned b = blocks_for(wanted_threads);
    threads += std::uint64_t(b) * threads_per_block;
    return b;
  }
};

inline void after_launch(const char* kernel) {
  check(cudaGetLastError(), kernel);
  check(cudaDeviceSynchronize(), kernel);
}

}  // namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE::ptsv
