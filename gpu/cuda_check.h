#pragma once
// Error checking for CUDA runtime calls: a failure after the device was found usable is an
// exception that names the call, never an abort.
#include <cuda_runtime_api.h>

namespace shadowcts {

// Throws std::runtime_error "CUDA error in <call>: <cudaGetErrorName>: <cudaGetErrorString>".
void check_cuda(cudaError_t status, const char* call);

}  // namespace shadowcts
