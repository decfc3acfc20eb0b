#pragma once
// The `cuda` backend of ptsv (ptsv_algorithm.h): NotSupported without a CUDA device.
#include <memory>

#include "shadowcts/algorithm.h"

namespace shadowcts {

std::unique_ptr<Algorithm> make_cuda_ptsv();

}  // namespace shadowcts
