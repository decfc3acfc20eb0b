#include "gpu/device.h"

#include <cuda_runtime_api.h>

#include <cstdio>
#include <stdexcept>

#include "gpu/cuda_check.h"

namespace shadowcts {

void check_cuda(cudaError_t status, const char* call) {
  if (status == cudaSuccess) return;
  throw std::runtime_error(std::string("CUDA error in ") + call + ": " + cudaGetErrorName(status) +
                           ": " + cudaGetErrorString(status));
}

namespace {

struct DeviceStatus {
  std::optional<std::string> unavailable_reason;
  std::string summary;
};

DeviceStatus unavailable(cudaError_t status) {
  cudaGetLastError();  // a failed query must not surface in a later, unrelated check
  return {std::string("no CUDA device: ") + cudaGetErrorString(status),
          std::string("no CUDA device (") + cudaGetErrorName(status) + ": " +
              cudaGetErrorString(status) + ")"};
}

DeviceStatus query_device_status() {
  int device_count = 0;
  if (const cudaError_t status = cudaGetDeviceCount(&device_count); status != cudaSuccess) {
    return unavailable(status);
  }
  if (device_count == 0) {
    return {"no CUDA device: cudaGetDeviceCount found none", "no CUDA device (0 devices)"};
  }
  int device = 0;
  if (const cudaError_t status = cudaGetDevice(&device); status != cudaSuccess) {
    return unavailable(status);
  }
  cudaDeviceProp properties{};
  if (const cudaError_t status = cudaGetDeviceProperties(&properties, device);
      status != cudaSuccess) {
    return unavailable(status);
  }
  char details[128];
  std::snprintf(details, sizeof details, " (sm_%d%d, %d SMs, %.1f GiB, device %d of %d)",
                properties.major, properties.minor, properties.multiProcessorCount,
                static_cast<double>(properties.totalGlobalMem) / (1024.0 * 1024.0 * 1024.0), device,
                device_count);
  return {std::nullopt, std::string(properties.name) + details};
}

// The device set does not change while the process runs; ask the driver once.
const DeviceStatus& device_status() {
  static const DeviceStatus status = query_device_status();
  return status;
}

}  // namespace

std::optional<std::string> cuda_unavailable_reason() {
  return device_status().unavailable_reason;
}

std::string cuda_device_summary() {
  return device_status().summary;
}

}  // namespace shadowcts
