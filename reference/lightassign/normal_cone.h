#pragma once
// Normal cones and Paper II's back-face culling of lights (Section 3.3, Figure 7): a light can be
// dropped for a cluster when omega > pi/2 + alpha + delta, omega the angle between the cone axis
// and the direction from the cluster's box centre to the light, alpha the cone's half angle and
// delta the half angle of the cone from the light around the box. Then every sample p of the box
// with a normal in the cone has n . (c - p) < 0: the angle between n and c - p is at least
// omega - alpha - delta.
//
// The definitions live in shadowcts/geometry/normal_cone.h (host and device, shared with the
// CUDA port); these are the reference's names for them.
#include <glm/vec3.hpp>

#include "shadowcts/algorithm.h"
#include "shadowcts/geometry/normal_cone.h"

namespace shadowcts {

// The implicit cone of a cube-face cell (quantize_normal's code): the axis through the cell's
// centre, the half angle to its farthest corner (a convex spherical quadrilateral within a
// hemisphere of the axis reaches its farthest point at a corner), plus the margin.
NormalCone normal_cell_cone(std::uint32_t code, std::uint32_t divisions);

// Accumulates the explicit cone of a set of normals (Paper II's "En"): the axis is the
// normalized sum of the unit normals, the half angle the largest angle to any of them.
class ExplicitNormalCone {
 public:
  void add_direction(const glm::vec3& n);
  // Call once all directions were added, then add each again to widen().
  NormalCone axis_only() const;
  static void widen(NormalCone& cone, const glm::vec3& n);

 private:
  geometry::ExplicitNormalConeSum sum_;
};

// Whether the light at `centre` faces away from every sample of `box` whose normal lies in the
// cone (the back-face rule above, with the margin on every angle).
bool light_behind_cone(const NormalCone& cone, const Aabb& box, const glm::dvec3& centre);

// The angle between two non-zero vectors, accurate near 0 and pi (atan2 of |a x b| and a . b).
double angle_between(const glm::dvec3& a, const glm::dvec3& b);

}  // namespace shadowcts
