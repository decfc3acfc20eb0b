#pragma once
// Tiled and clustered light assignment on a CUDA device (gpu/lightassign/lightassign_kernels.cuh).
#include <memory>

#include "shadowcts/algorithm.h"

namespace shadowcts {

// id "lightassign", backend "cuda"; NotSupported without a device.
std::unique_ptr<Algorithm> make_lightassign_cuda();

}  // namespace shadowcts
