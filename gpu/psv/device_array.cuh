#pragma once
// Device memory for the psv kernels: one owned allocation per array, and CUDA errors as
// exceptions.
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "gpu/emulator/kernel.h"

namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE {
namespace psv {

inline void check(cudaError_t status, const char* call) {
  if (status == cudaSuccess) return;
  throw std::runtime_error(std::string("CUDA error in ") + call + ": " + cudaGetErrorName(status) +
                           ": " + cudaGetErrorString(status));
}

// Owns one device allocation.
template <typename T>
class DeviceArray {
 public:
  explicit DeviceArray(std::size_t count) : count_(count) {
    if (count_ != 0) check(cudaMalloc(&data_, count_ * sizeof(T)), "cudaMalloc");
  }
  DeviceArray(const DeviceArray&) = delete;
  DeviceArray& operator=(const DeviceArray&) = delete;
  ~DeviceArray() {
    if (data_ != nullptr) cudaFree(data_);  // nothing useful to do with an error in a destructor
  }
  T* data() const { return data_; }

  void upload(const std::vector<T>& host) {
    if (count_ != 0) {
      check(cudaMemcpy(data_, host.data(), count_ * sizeof(T), cudaMemcpyHostToDevice),
            "cudaMemcpy to device");
    }
  }
  // host[0, count) into elements [offset, offset + count).
  void upload(const T* host, std::size_t offset, std::size_t count) {
    if (count != 0) {
      check(cudaMemcpy(data_ + offset, host, count * sizeof(T), cudaMemcpyHostToDevice),
            "cudaMemcpy to device");
    }
  }
  void zero() {
    if (count_ != 0) check(cudaMemset(data_, 0, count_ * sizeof(T)), "cudaMemset");
  }
  void download(T* host) const { download(host, count_); }
  // Elements [0, count) into host.
  void download(T* host, std::size_t count) const {
    if (count != 0) {
      check(cudaMemcpy(host, data_, count * sizeof(T), cudaMemcpyDeviceToHost),
            "cudaMemcpy to host");
    }
  }

 private:
  std::size_t count_;
  T* data_ = nullptr;
};

}  // namespace psv
}  // namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE
