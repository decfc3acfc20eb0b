#pragma once
// Normal cones and Paper II's back-face culling of lights (Section 3.3, Figure 7), for host and
// device: the definition the reference (reference/lightassign/normal_cone.h) and the CUDA port
// share. A light can be dropped for a cluster when omega > pi/2 + alpha + delta, omega the angle
// between the cone axis and the direction from the cluster's box centre to the light, alpha the
// cone's half angle and delta the half angle of the cone from the light around the box.
//
// Every operation is one IEEE rounding (rounded_arithmetic.h) in glm's order (dot: (x + y) + z;
// normalize: v * (1 / sqrt(v . v))), so host and device compute the same doubles up to the
// transcendental functions (atan2, asin), whose device versions may differ from glibc's by an ulp.
#include <cmath>
#include <cstdint>

#include <glm/vec3.hpp>

#include "shadowcts/geometry/rounded_arithmetic.h"
#include "shadowcts/host_device.h"

namespace shadowcts {
SHADOWCTS_GEOMETRY_ABI_BEGIN

struct NormalCone {
  glm::dvec3 axis{0.0, 0.0, 1.0};  // unit
  double half_angle = 3.2;         // radians; >= pi: no culling
};

// Margin added to every angle of the rule (radians): far above the rounding of the few double
// operations behind each angle, far below anything the culling could use.
inline constexpr double normal_cone_margin = 1e-6;

namespace geometry {

inline constexpr double cone_pi = 3.14159265358979323846;

SHADOWCTS_HD inline double cone_dot(const glm::dvec3& a, const glm::dvec3& b) {
  return rounded_add(rounded_add(rounded_mul(a.x, b.x), rounded_mul(a.y, b.y)),
                     rounded_mul(a.z, b.z));
}

SHADOWCTS_HD inline double cone_length(const glm::dvec3& a) {
  return sqrt(cone_dot(a, a));
}

SHADOWCTS_HD inline glm::dvec3 cone_cross(const glm::dvec3& x, const glm::dvec3& y) {
  return {rounded_sub(rounded_mul(x.y, y.z), rounded_mul(y.y, x.z)),
          rounded_sub(rounded_mul(x.z, y.x), rounded_mul(y.z, x.x)),
          rounded_sub(rounded_mul(x.x, y.y), rounded_mul(y.x, x.y))};
}

SHADOWCTS_HD inline glm::dvec3 cone_scaled(const glm::dvec3& v, double s) {
  return {rounded_mul(v.x, s), rounded_mul(v.y, s), rounded_mul(v.z, s)};
}

SHADOWCTS_HD inline glm::dvec3 cone_divided(const glm::dvec3& v, double s) {
  return {v.x / s, v.y / s, v.z / s};
}

SHADOWCTS_HD inline glm::dvec3 cone_normalize(const glm::dvec3& v) {
  return cone_scaled(v, 1.0 / sqrt(cone_dot(v, v)));
}

// The angle between two non-zero vectors, accurate near 0 and pi (atan2 of |a x b| and a . b).
SHADOWCTS_HD inline double cone_angle_between(const glm::dvec3& a, const glm::dvec3& b) {
  return atan2(cone_length(cone_cross(a, b)), cone_dot(a, b));
}

// The implicit cone of a cube-face cell (quantize_normal's code): the axis through the cell's
// centre, the half angle to its farthest corner (a convex spherical quadrilateral within a
// hemisphere of the axis reaches its farthest point at a corner), plus the margin.
SHADOWCTS_HD inline NormalCone normal_cell_cone(std::uint32_t code, std::uint32_t divisions) {
  const std::uint32_t face = code / (divisions * divisions);
  const std::uint32_t row = (code / divisions) % divisions, column = code % divisions;
  const int axis = int(face / 2);
  const double sign = face % 2 == 0 ? 1.0 : -1.0;
  const int u_axis = axis == 0 ? 1 : 0, v_axis = axis == 2 ? 1 : 2;
  // The direction of face point (u, v) in [-1, 1]^2.
  auto direction = [&](double u, double v) {
    glm::dvec3 d(0.0);
    d[axis] = sign;
    d[u_axis] = u;
    d[v_axis] = v;
    return cone_normalize(d);
  };
  const double step = 2.0 / divisions;
  const double u0 = rounded_add(-1.0, rounded_mul(step, double(column)));
  const double v0 = rounded_add(-1.0, rounded_mul(step, double(row)));
  const double half_step = rounded_mul(0.5, step);
  NormalCone cone;
  cone.axis = direction(rounded_add(u0, half_step), rounded_add(v0, half_step));
  double widest = 0.0;
  const double us[2] = {u0, rounded_add(u0, step)}, vs[2] = {v0, rounded_add(v0, step)};
  for (const double u : us)
    for (const double v : vs) {
      const double angle = cone_angle_between(cone.axis, direction(u, v));
      if (widest < angle) widest = angle;
    }
  cone.half_angle = rounded_add(widest, normal_cone_margin);
  return cone;
}

// Accumulates the explicit cone of a set of normals (Paper II's "En"): the axis is the
// normalized sum of the unit normals, the half angle the largest angle to any of them.
struct ExplicitNormalConeSum {
  glm::dvec3 sum{0.0};

  SHADOWCTS_HD void add_direction(const glm::vec3& n) {
    const glm::dvec3 d(n);
    const double length = cone_length(d);
    if (length > 0.0) {
      const glm::dvec3 unit = cone_divided(d, length);
      sum = {rounded_add(sum.x, unit.x), rounded_add(sum.y, unit.y), rounded_add(sum.z, unit.z)};
    }
  }

  // Call once all directions were added, then add each again to widen().
  SHADOWCTS_HD NormalCone axis_only() const {
    NormalCone cone;
    const double length = cone_length(sum);
    if (!(length > 1e-9)) {
      cone.half_angle = 2.0 * cone_pi;  // no usable axis: the cone is everything
      return cone;
    }
    cone.axis = cone_divided(sum, length);
    cone.half_angle = 0.0;
    return cone;
  }

  SHADOWCTS_HD static void widen(NormalCone& cone, const glm::vec3& n) {
    if (cone.half_angle >= cone_pi) return;
    const glm::dvec3 d(n);
    if (!(cone_length(d) > 0.0)) return;
    const double angle = rounded_add(cone_angle_between(cone.axis, d), normal_cone_margin);
    if (cone.half_angle < angle) cone.half_angle = angle;
  }
};

// Whether the light at `centre` faces away from every sample of the box [low, high] whose normal
// lies in the cone (the back-face rule above, with the margin on every angle).
SHADOWCTS_HD inline bool light_behind_cone(const NormalCone& cone, const glm::vec3& box_min,
                                           const glm::vec3& box_max, const glm::dvec3& centre) {
  const double alpha = cone.half_angle;
  if (alpha >= cone_pi / 2) return false;  // omega <= pi can never exceed pi/2 + alpha
  const glm::dvec3 low(box_min), high(box_max);
  const glm::dvec3 middle = cone_scaled(
      {rounded_add(low.x, high.x), rounded_add(low.y, high.y), rounded_add(low.z, high.z)}, 0.5);
  const glm::dvec3 extent{rounded_sub(high.x, low.x), rounded_sub(high.y, low.y),
                          rounded_sub(high.z, low.z)};
  const double radius = rounded_mul(rounded_mul(0.5, cone_length(extent)), 1.0 + 1e-12);
  const glm::dvec3 to_light{rounded_sub(centre.x, middle.x), rounded_sub(centre.y, middle.y),
                            rounded_sub(centre.z, middle.z)};
  const double distance = cone_length(to_light);
  // The light is within the box's sphere: nothing to cull.
  if (!(distance > rounded_mul(radius, 1.0 + 1e-9))) return false;
  const double ratio = radius / distance;
  const double delta = asin(ratio < 1.0 ? ratio : 1.0);
  const double omega = cone_angle_between(cone.axis, to_light);
  return omega >
         rounded_add(rounded_add(rounded_add(cone_pi / 2, alpha), delta), 2.0 * normal_cone_margin);
}

}  // namespace geometry
SHADOWCTS_GEOMETRY_ABI_END
}  // namespace shadowcts
