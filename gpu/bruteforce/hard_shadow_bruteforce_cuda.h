#pragma once
// Brute-force hard shadows on a CUDA device: every regular view sample against every caster
// triangle, with the watertight float32 test of shadowcts/geometry/segment_triangle.h.
#include <memory>

#include "shadowcts/algorithm.h"

namespace shadowcts {

// id "bruteforce", backend "cuda", variant "float32"; reports "pair_tests".
std::unique_ptr<Algorithm> make_bruteforce_hard_shadow_cuda();

}  // namespace shadowcts
