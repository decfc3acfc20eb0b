#pragma once
// The reference `lightassign`: tiled (Paper I) and clustered (Paper II) light assignment, and the
// per-sample exact lists. Variants:
//   tiled          32x32 tiles, per-tile min/max depth sub-frusta, per-light tile insertion
//   clustered      tile x exponential depth slice, implicit bounds, 32-wide light BVH
//   clustered+eb   explicit bounds (AABB of the cluster's samples)
//   clustered+en   explicit normal cones with the back-face rule
//   clustered+nk3  normal clustering, 3x3 cells per cube face, implicit cones
//   brute          per-sample exact sets (optimal efficiency)
// Counters: see light_assignment_counters() in light_list_builder.h.
#include <memory>

#include "shadowcts/algorithm.h"

namespace shadowcts {

// id "lightassign", backend "reference", output light_lists, capability ranged_lights.
std::unique_ptr<Algorithm> make_lightassign();

}  // namespace shadowcts
