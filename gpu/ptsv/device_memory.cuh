#pragma once
// Device allocations and copies of the CUDA ptsv (both builds: nvcc and the emulator).
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "gpu/emulator/kernel.h"

namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE::ptsv {

inline void check(cudaError_t status, const char* call) {
  if (status == cudaSuccess) return;
  throw std::runtime_error(std::string("ptsv: CUDA error in ") + call + ": " +
                           cudaGetErrorName(status) + ": " + cudaGetErrorString(status));
}

// Owns one device allocation of `size` elements (none for size 0).
template <typename T>
class DeviceArray {
 public:
  DeviceArray() = default;
  explicit DeviceArray(std::size_t size) { resize(size); }
  DeviceArray(const DeviceArray&) = delete;
  DeviceArray& operator=(const DeviceArray&) = delete;
  DeviceArray(DeviceArray&& other) noexcept : size_(other.size_), data_(other.data_) {
    other.size_ = 0;
    other.data_ = nullptr;
  }
  DeviceArray& operator=(DeviceArray&& other) noexcept {
    if (this != &other) {
      release();
      size_ = other.size_;
      data_ = other.data_;
      other.size_ = 0;
      other.data_ = nullptr;
    }
    return *this;
  }
  ~DeviceArray() { release(); }

  void resize(std::size_t size) {
    release();
    size_ = size;
    if (size_ != 0) check(cudaMalloc(&data_, size_ * sizeof(T)), "cudaMalloc");
  }
  T* data() const { return data_; }
  std::size_t size() const { return size_; }

  void upload(const std::vector<T>& host) {
    resize(host.size());
    if (size_ != 0)
      check(cudaMemcpy(data_, host.data(), size_ * sizeof(T), cudaMemcpyHostToDevice),
            "cudaMemcpy to device");
  }
  std::vector<T> download() const { return download(size_); }
  std::vector<T> download(std::size_t count) const {
    std::vector<T> host(count);
    if (count != 0)
      check(cudaMemcpy(host.data(), data_, count * sizeof(T), cudaMemcpyDeviceToHost),
            "cudaMemcpy to host");
    return host;
  }
  T at(std::size_t i) const {
    T value;
    check(cudaMemcpy(&value, data_ + i, sizeof(T), cudaMemcpyDeviceToHost), "cudaMemcpy to host");
    return value;
  }
  void set(std::size_t i, const T& value) {
    check(cudaMemcpy(data_ + i, &value, sizeof(T), cudaMemcpyHostToDevice), "cudaMemcpy to device");
  }
  void zero() {
    if (size_ != 0) check(cudaMemset(data_, 0, size_ * sizeof(T)), "cudaMemset");
  }

 private:
  void release() {
    if (data_ != nullptr) cudaFree(data_);  // nothing useful to do with an error here
    data_ = nullptr;
    size_ = 0;
  }
  std::size_t size_ = 0;
  T* data_ = nullptr;
};

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
