#include "simd/psv/plane_side.h"

namespace shadowcts::simd::psv {

int PlaneSide::near_side(const ref::TopTree& tree, std::uint32_t node, const VolumeCorners& corners,
                         const glm::dvec3& p) const {
  const std::uint32_t k = node % ref::nodes_per_volume;
  const auto at = [&](std::uint32_t i) { return glm::dvec3(corners[i]) == p; };
  if (k == ref::capping_plane) {
    if (at(0) || at(1) || at(2)) return 0;
  } else if (at(k) || at((k + 1) % 3)) {
    // An edge plane holds its edge (and the light): a neighbour sharing the edge's vertices, the
    // common case of a tessellated surface, needs no exact predicate for them.
    return 0;
  }
  return exact_.side(tree, node, p);
}

}  // namespace shadowcts::simd::psv
