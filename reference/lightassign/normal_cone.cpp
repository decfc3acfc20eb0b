#include "reference/lightassign/normal_cone.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

namespace shadowcts {

double angle_between(const glm::dvec3& a, const glm::dvec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

NormalCone normal_cell_cone(std::uint32_t code, std::uint32_t divisions) {
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
    return glm::normalize(d);
  };
  const double step = 2.0 / divisions;
  const double u0 = -1.0 + step * column, v0 = -1.0 + step * row;
  NormalCone cone;
  cone.axis = direction(u0 + 0.5 * step, v0 + 0.5 * step);
  double widest = 0.0;
  for (const double u : {u0, u0 + step})
    for (const double v : {v0, v0 + step})
      widest = std::max(widest, angle_between(cone.axis, direction(u, v)));
  cone.half_angle = widest + normal_cone_margin;
  return cone;
}

void ExplicitNormalCone::add_direction(const glm::vec3& n) {
  const glm::dvec3 d(n);
  const double length = glm::length(d);
  if (length > 0.0) sum_ += d / length;
}

NormalCone ExplicitNormalCone::axis_only() const {
  NormalCone cone;
  const double length = glm::length(sum_);
  if (!(length > 1e-9)) {
    cone.half_angle = 2.0 * std::numbers::pi;  // no usable axis: the cone is everything
    return cone;
  }
  cone.axis = sum_ / length;
  cone.half_angle = 0.0;
  return cone;
}

void ExplicitNormalCone::widen(NormalCone& cone, const glm::vec3& n) {
  if (cone.half_angle >= std::numbers::pi) return;
  const glm::dvec3 d(n);
  if (!(glm::length(d) > 0.0)) return;
  cone.half_angle = std::max(cone.half_angle, angle_between(cone.axis, d) + normal_cone_margin);
}

bool light_behind_cone(const NormalCone& cone, const Aabb& box, const glm::dvec3& centre) {
  const double alpha = cone.half_angle;
  if (alpha >= std::numbers::pi / 2) return false;  // omega <= pi can never exceed pi/2 + alpha
  const glm::dvec3 low(box.min), high(box.max);
  const glm::dvec3 middle = 0.5 * (low + high);
  const double radius = 0.5 * glm::length(high - low) * (1.0 + 1e-12);
  const glm::dvec3 to_light = centre - middle;
  const double distance = glm::length(to_light);
  if (!(distance > radius * (1.0 + 1e-9))) return false;  // the light is within the box's sphere
  const double delta = std::asin(std::min(1.0, radius / distance));
  const double omega = angle_between(cone.axis, to_light);
  return omega > std::numbers::pi / 2 + alpha + delta + 2.0 * normal_cone_margin;
}

}  // namespace shadowcts
