#pragma once
// The CUDA device this process would run kernels on, asked once. Never aborts: a missing driver
// or a machine without a GPU is an answer, not an error.
#include <optional>
#include <string>

namespace shadowcts {

// nullopt when kernels can run; otherwise "no CUDA device: <cudaGetErrorString>".
std::optional<std::string> cuda_unavailable_reason();

// One line for logs and reports: "<name> (sm_90, 132 SMs, 79.2 GiB)", or
// "no CUDA device (cudaErrorInsufficientDriver: CUDA driver version is insufficient ...)".
std::string cuda_device_summary();

}  // namespace shadowcts
