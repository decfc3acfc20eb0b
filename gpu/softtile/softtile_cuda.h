#pragma once
// `softtile` on a CUDA device (gpu/softtile/softtile_algorithm.h); NotSupported without one.
#include <memory>

#include "shadowcts/algorithm.h"

namespace shadowcts {

// id "softtile", backend "cuda".
std::unique_ptr<Algorithm> make_softtile_cuda();

}  // namespace shadowcts
