#pragma once
// How far a long kernel is, for the progress line (shadowcts/phase_progress.h): each block adds
// one to a counter in device memory when it starts (count_started_block), and the host reads the
// counter while it waits for the kernel (KernelProgress::wait).
//
// On a device the wait polls: the kernel runs in the default stream, and the counter is copied
// on a stream of its own that does not synchronize with it. Under the emulator a launch returns
// when all its blocks are done, and the emulator reports them itself (gpu/emulator); there the
// wait checks that the kernel counted each of its blocks exactly once, so every emulated run
// checks the counting that the progress on a device relies on.
#include <chrono>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <thread>

#include "gpu/device_array.cuh"
#include "gpu/emulator/kernel.h"
#include "shadowcts/phase_progress.h"

namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE {

// The first statement of a kernel whose progress is shown (one-dimensional blocks).
__device__ inline void count_started_block(unsigned long long* blocks_started) {
  if (threadIdx.x == 0) atomicAdd(blocks_started, 1ull);
}

class KernelProgress {
 public:
  KernelProgress() : counter_(1) { counter_.zero(); }

  // The counter to hand to the kernel: zero at its launch.
  unsigned long long* counter() const { return counter_.data(); }

  // After launching `blocks` blocks of `kernel` (a string literal: the progress line keeps it):
  // waits for the kernel, throws on its errors, and sets the counter back to zero.
  void wait(const char* kernel, std::uint64_t blocks) {
    check(cudaGetLastError(), kernel);
#if SHADOWCTS_EMULATED
    check(cudaDeviceSynchronize(), kernel);
    const unsigned long long counted = counter_.at(0);
    if (counted != blocks)
      throw std::logic_error(std::string(kernel) + ": the kernel counted " +
                             std::to_string(counted) + " started blocks of " +
                             std::to_string(blocks));
#else
    phase_progress::begin(blocks, "blocks", kernel);
    std::uint64_t reported = 0;
    const cudaError_t status = poll(blocks, reported);
    check(status, kernel);
    check(cudaDeviceSynchronize(), kernel);
    if (blocks > reported) phase_progress::advance(blocks - reported);
#endif
    counter_.zero();
  }

 private:
#if !SHADOWCTS_EMULATED
  // Until the default stream is idle: its status, and the blocks passed on to the progress line.
  // The first millisecond spins, so that short kernels pay neither a sleep nor the reading
  // stream and its pinned word, which are made only then.
  cudaError_t poll(std::uint64_t blocks, std::uint64_t& reported) const {
    cudaStream_t stream = nullptr;
    unsigned long long* seen = nullptr;
    bool can_read = false, made = false;
    const auto start = std::chrono::steady_clock::now();
    cudaError_t status = cudaSuccess;
    while ((status = cudaStreamQuery(nullptr)) == cudaErrorNotReady) {
      if (std::chrono::steady_clock::now() - start < std::chrono::milliseconds(1)) {
        std::this_thread::yield();
        continue;
      }
      if (!made) {
        made = true;
        can_read = cudaStreamCreateWithFlags(&stream, cudaStreamNonBlocking) == cudaSuccess &&
                   cudaMallocHost(&seen, sizeof *seen) == cudaSuccess;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
      if (can_read &&
          cudaMemcpyAsync(seen, counter_.data(), sizeof *seen, cudaMemcpyDeviceToHost, stream) ==
              cudaSuccess &&
          cudaStreamSynchronize(stream) == cudaSuccess && *seen > reported && *seen <= blocks) {
        phase_progress::advance(*seen - reported);
        reported = *seen;
      }
    }
    if (seen != nullptr) cudaFreeHost(seen);
    if (stream != nullptr) cudaStreamDestroy(stream);
    return status;
  }
#endif

  DeviceArray<unsigned long long> counter_;
};

}  // namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE
