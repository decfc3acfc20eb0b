#pragma once
// Exact orientation predicates on double coordinates (every float input is a double exactly):
// the signs every plane test of the TOP tree falls back to when floating point cannot decide.
#include <glm/vec3.hpp>

namespace shadowcts::psv {

// Sign of det[q - p, r - p, s - p]: CGAL's filtered exact orientation.
int orientation_sign(const glm::dvec3& p, const glm::dvec3& q, const glm::dvec3& r,
                     const glm::dvec3& s);

// Sign of det[b - a, direction, s - a]: the side of s against the plane through a and b that
// contains the direction. Filtered in double, exact rationals when the filter cannot decide.
int direction_orientation_sign(const glm::dvec3& a, const glm::dvec3& b,
                               const glm::dvec3& direction, const glm::dvec3& s);

}  // namespace shadowcts::psv
