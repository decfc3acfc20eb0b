#pragma once
// simd `metric`: the Highway + oneTBB port of reference/metric (Deves et al. 2018): the
// reference's clustering, the tree built in parallel, packet traversal in Highway lanes.
#include <memory>

#include "shadowcts/algorithm.h"

namespace shadowcts {

// id "metric", backend "simd"; variants "capsules" (default), "spheres" and "capsules16" (the
// insertion-build variants of the reference; "median" is not ported).
std::unique_ptr<Algorithm> make_simd_metric();

}  // namespace shadowcts
