#pragma once
// The depth of Mora 2016, section 3.3: a volume's distance from the light, and a query point's.
// A point closer to the light than every triangle of a subtree lies in none of their shadow
// volumes (each volume point is L + s (y - L) with y on the triangle and s >= 1), so the subtree
// can be skipped. Both sides of that comparison are bounded the safe way: triangle depths are
// lower bounds rounded down to float, sample depths upper bounds, so a skip is never wrong.
//
// Point light: Euclidean distance to L. Directional light (d towards the light): the light
// distance is -d . x up to a constant, and a volume point y - t d (t >= 0) only gets farther.
#include <glm/vec3.hpp>

#include "shadowcts/case.h"
#include "shadowcts/hard_shadow_inputs.h"

namespace shadowcts::psv {

// Lower bound on min over the closed triangle of the light distance, rounded down to float.
float triangle_light_depth(const HardShadowLight& light, const Triangle& t);

// Upper bound on the light distance of the point p (a view sample).
double sample_light_depth(const HardShadowLight& light, const glm::dvec3& p);

}  // namespace shadowcts::psv
