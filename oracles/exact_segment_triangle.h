#pragma once
// The exact hard-shadow predicate: does a closed triangle meet the shadow segment (point light) or
// the shadow ray (directional light) of a sample position that may have been moved by the band?
// Exact for float triangle vertices, float lights and exactly represented moved positions: CGAL's
// orientation predicates decide, no plane or intersection point is ever constructed in floating
// point, and no coordinate is ever rounded.
#include <glm/vec3.hpp>

#include "oracles/hard_shadow_inputs.h"
#include "shadowcts/case.h"

namespace shadowcts {

// The point base + delta * direction, with direction's components in {-1, 0, 1}: a sample
// position moved by the ambiguity band. Its coordinates are exact: the predicate evaluates the sum
// in doubles only where that is provably exact, and in exact rationals otherwise.
struct MovedPoint {
  glm::dvec3 base{0.0};
  double delta = 0.0;
  glm::ivec3 direction{0};
};

// Whether the three vertices are exactly collinear (the triangle has zero area and casts no
// shadow).
bool is_zero_area(const Triangle& t);

class ExactShadowPredicate {
 public:
  // scene_bound must be >= every |coordinate| of every triangle passed to blocks(): directional
  // rays are cut where they leave that cube.
  ExactShadowPredicate(const HardShadowLight& light, double scene_bound);

  // Does the closed triangle t meet the closed segment from x to the point light, or the closed
  // ray from x towards the directional light? False for zero-area triangles. The caller excludes
  // the receiver and non-caster triangles.
  bool blocks(const Triangle& t, const MovedPoint& x) const;

 private:
  HardShadowLight light_;
  double scene_bound_;
};

}  // namespace shadowcts
