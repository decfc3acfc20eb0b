#include "reference/lightassign/normal_cone.h"

namespace shadowcts {

double angle_between(const glm::dvec3& a, const glm::dvec3& b) {
  return geometry::cone_angle_between(a, b);
}

NormalCone normal_cell_cone(std::uint32_t code, std::uint32_t divisions) {
  return geometry::normal_cell_cone(code, divisions);
}

void ExplicitNormalCone::add_direction(const glm::vec3& n) {
  sum_.add_direction(n);
}

NormalCone ExplicitNormalCone::axis_only() const {
  return sum_.axis_only();
}

void ExplicitNormalCone::widen(NormalCone& cone, const glm::vec3& n) {
  geometry::ExplicitNormalConeSum::widen(cone, n);
}

bool light_behind_cone(const NormalCone& cone, const Aabb& box, const glm::dvec3& centre) {
  return geometry::light_behind_cone(cone, box.min, box.max, centre);
}

}  // namespace shadowcts
