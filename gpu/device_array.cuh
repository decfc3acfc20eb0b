#pragma once
// Device memory of every kernel family, for both builds (gpu/emulator/kernel.h maps the runtime
// calls onto the emulator's host memory): one owned allocation per array, and CUDA errors as
// exceptions that name the call.
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "gpu/emulator/kernel.h"

namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE {

inline void check(cudaError_t status, const char* call) {
  if (status == cudaSuccess) return;
  throw std::runtime_error(std::string("CUDA error in ") + call + ": " + cudaGetErrorName(status) +
                           ": " + cudaGetErrorString(status));
}

// Owns one device allocation of size() elements (none for size 0).
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

  // Drops the contents.
  void resize(std::size_t size) {
    release();
    size_ = size;
    if (size_ != 0) check(cudaMalloc(&data_, size_ * sizeof(T)), "cudaMalloc");
  }
  T* data() const { return data_; }
  std::size_t size() const { return size_; }

  // The whole of `host`, resizing to it.
  void upload(const std::vector<T>& host) {
    if (host.size() != size_) resize(host.size());
    upload(host.data(), 0, size_);
  }
  // host[0, count) into elements [offset, offset + count).
  void upload(const T* host, std::size_t offset, std::size_t count) {
    if (count != 0)
      check(cudaMemcpy(data_ + offset, host, count * sizeof(T), cudaMemcpyHostToDevice),
            "cudaMemcpy to device");
  }
  // Elements [0, count) into host.
  void download(T* host, std::size_t count) const {
    if (count != 0)
      check(cudaMemcpy(host, data_, count * sizeof(T), cudaMemcpyDeviceToHost),
            "cudaMemcpy to host");
  }
  void download(T* host) const { download(host, size_); }
  std::vector<T> download(std::size_t count) const {
    std::vector<T> host(count);
    download(host.data(), count);
    return host;
  }
  std::vector<T> download() const { return download(size_); }
  T at(std::size_t i) const {
    T value;
    check(cudaMemcpy(&value, data_ + i, sizeof(T), cudaMemcpyDeviceToHost), "cudaMemcpy to host");
    return value;
  }
  void set(std::size_t i, const T& value) {
    check(cudaMemcpy(data_ + i, &value, sizeof(T), cudaMemcpyHostToDevice), "cudaMemcpy to device");
  }
  void fill_bytes(int byte) {
    if (size_ != 0) check(cudaMemset(data_, byte, size_ * sizeof(T)), "cudaMemset");
  }
  void zero() { fill_bytes(0); }

 private:
  void release() {
    if (data_ != nullptr) cudaFree(data_);  // nothing useful to do with an error here
    data_ = nullptr;
    size_ = 0;
  }
  std::size_t size_ = 0;
  T* data_ = nullptr;
};

// Uploads a host staging array and frees it: from here on the device's copy is the only one.
// Under the emulator device memory is host memory, so keeping the staging array would hold the
// samples twice while the kernels run (docs/specification.md, "Memory").
template <typename T>
DeviceArray<T> upload_and_free(std::vector<T>& host) {
  DeviceArray<T> device;
  device.upload(host);
  std::vector<T>().swap(host);
  return device;
}

}  // namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE
