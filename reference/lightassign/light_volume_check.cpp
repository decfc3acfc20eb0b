#include "reference/lightassign/light_volume_check.h"

#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "shadowcts/geometry/sphere_box.h"

namespace shadowcts {

LightVolumeCheck::LightVolumeCheck(const RangedLight& l) : light(l) {
  if (light.kind == RangedLightKind::spot) {
    cos_half_angle = std::cos(double(light.cone_half_angle));
    axis_length = glm::length(glm::dvec3(light.direction));
  }
}

int LightVolumeCheck::contains(const glm::vec3& x) const {
  if (!geometry::sphere_meets_box(light.centre, light.range, x, x)) return 0;
  if (light.kind != RangedLightKind::spot) return 1;
  // angle(x - c, axis) <= half angle  <=>  (x - c) . a - |x - c| |a| cos(half angle) >= 0; the
  // apex (x == c) belongs to the cone.
  const glm::dvec3 d = glm::dvec3(x) - glm::dvec3(light.centre);
  const glm::dvec3 a(light.direction);
  const double length = glm::length(d);
  const double margin = glm::dot(d, a) - length * axis_length * cos_half_angle;
  // Each of the ~20 roundings (the differences, products, sums, square roots and libm's cos,
  // which errs by less than one ulp) is within 2^-53 relative of a term bounded by |d| |a|: 2^-46
  // |d| |a| bounds their sum with a wide margin; the last term covers underflow.
  const double bound = 0x1p-46 * length * axis_length + std::numeric_limits<double>::min();
  if (margin > bound) return 1;
  if (margin < -bound) return 0;
  return length == 0.0 ? 1 : -1;
}

}  // namespace shadowcts
