#pragma once
// The simd `lightassign` (Highway + oneTBB): the port of reference/lightassign/ for the variants
// tiled, clustered, clustered+eb, clustered+en and clustered+nk3, with the reference's lists,
// bounds, list_of_sample and counters (tests/simd/lightassign/ diff them). Not ported: brute (its
// per-sample cull is the exact light-volume predicate of the oracle library, which simd/ may not
// use).
#include <memory>

#include "shadowcts/algorithm.h"

namespace shadowcts {

// id "lightassign", backend "simd", output light_lists, capability ranged_lights.
std::unique_ptr<Algorithm> make_simd_lightassign();

}  // namespace shadowcts
