#pragma once
// Device allocations and transfers of the lightassign kernels, for both builds (gpu/emulator/
// kernel.h maps the runtime calls onto the emulator's host memory).
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

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

inline void check(cudaError_t status, const char* call) {
  if (status == cudaSuccess) return;
  throw std::runtime_error(std::string("lightassign: CUDA error in ") + call + ": " +
                           cudaGetErrorName(status) + ": " + cudaGetErrorString(status));
}

// Owns one device allocation of `count` elements.
template <typename T>
class DeviceArray {
 public:
  DeviceArray() = default;
  explicit DeviceArray(std::size_t count) { resize(count); }
  DeviceArray(const DeviceArray&) = delete;
  DeviceArray& operator=(const DeviceArray&) = delete;
  ~DeviceArray() { release(); }

  // Drops the contents.
  void resize(std::size_t count) {
    release();
    count_ = count;
    if (count_ != 0) check(cudaMalloc(&data_, count_ * sizeof(T)), "cudaMalloc");
  }
  T* data() const { return data_; }
  std::size_t size() const { return count_; }

  void upload(const std::vector<T>& host) {
    if (host.size() != count_) resize(host.size());
    if (count_ != 0)
      check(cudaMemcpy(data_, host.data(), count_ * sizeof(T), cudaMemcpyHostToDevice),
            "cudaMemcpy to device");
  }
  std::vector<T> download(std::size_t count) const {
    std::vector<T> host(count);
    if (count != 0)
      check(cudaMemcpy(host.data(), data_, count * sizeof(T), cudaMemcpyDeviceToHost),
            "cudaMemcpy to host");
    return host;
  }
  std::vector<T> download() const { return download(count_); }
  T at(std::size_t i) const {
    T value;
    check(cudaMemcpy(&value, data_ + i, sizeof(T), cudaMemcpyDeviceToHost), "cudaMemcpy to host");
    return value;
  }
  void fill_bytes(int byte) {
    if (count_ != 0) check(cudaMemset(data_, byte, count_ * sizeof(T)), "cudaMemset");
  }

 private:
  void release() {
    if (data_ != nullptr) cudaFree(data_);  // nothing useful to do with an error here
    data_ = nullptr;
    count_ = 0;
  }
  std::size_t count_ = 0;
  T* data_ = nullptr;
};

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
