#include "reference/softtile/shadow_cone.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace shadowcts::softtile {
namespace {

constexpr double relative_margin = 1e-9;

// The shadow cone: apex at the tip, axis -d, half-angle a.
struct Cone {
  glm::dvec3 apex{0.0};
  glm::dvec3 axis{0.0};
  double cos_half_angle = 1.0, sin_half_angle = 0.0;
};

// Distance from x to the cone (0 inside), minus what the bound's radius there covers. In the
// plane of the axis and x, with h the height along the axis and l the lateral distance, the cone
// is the wedge below the ray (cos a, sin a): its nearest point is the apex when x lies in the
// wedge's polar cone, otherwise on the ray.
double gap(const Cone& cone, const glm::dvec3& x, double radius) {
  const double slack = relative_margin * (glm::length(x - cone.apex) + radius);
  const glm::dvec3 v = x - cone.apex;
  const double h = glm::dot(v, cone.axis);
  const double l = glm::length(v - h * cone.axis);
  const double c = cone.cos_half_angle, s = cone.sin_half_angle;
  const double distance = h * c + l * s <= 0.0 ? glm::length(v) : std::max(0.0, l * c - h * s);
  return distance - radius - slack;
}

}  // namespace

ShadowCone shadow_cone(const SunGeometry& sun, const glm::dvec3& centre, double radius,
                       double highest) {
  ShadowCone cone;
  // A cone of half-angle a contains a sphere of radius r whose centre lies r / sin(a) down its
  // axis; widen by a relative margin so rounding cannot leave the sphere poking out.
  cone.tip = centre + sun.direction * (radius * (1.0 + 1e-9) / std::sin(sun.angular_radius));
  cone.start_height = glm::dot(cone.tip, sun.direction) - highest;
  return cone;
}

bool may_shadow(const SunGeometry& sun, const ShadowCone& shadow, const TileBound& bound) {
  const Cone cone{shadow.tip, -sun.direction, std::cos(sun.angular_radius),
                  std::sin(sun.angular_radius)};
  const auto height = [&](const glm::dvec3& x) { return glm::dot(shadow.tip - x, sun.direction); };
  const double height_slack =
      relative_margin * (glm::length(shadow.tip) + glm::length(bound.a) + glm::length(bound.b) +
                         bound.radius_a + bound.radius_b);
  if (!bound.capsule) {
    if (height(bound.a) + bound.radius_a < shadow.start_height - height_slack) return false;
    return gap(cone, bound.a, bound.radius_a) <= 0.0;
  }
  // Truncation: the capsule's highest reach below the tip is at one of its end spheres.
  if (std::max(height(bound.a) + bound.radius_a, height(bound.b) + bound.radius_b) <
      shadow.start_height - height_slack)
    return false;
  // Cheap reject first: the sphere around the whole capsule.
  const glm::dvec3 middle = 0.5 * (bound.a + bound.b);
  const double enclosing =
      0.5 * glm::length(bound.b - bound.a) + std::max(bound.radius_a, bound.radius_b);
  if (gap(cone, middle, enclosing) > 0.0) return false;
  // g(s) = distance(axis point, cone) - radius(s) is convex (distance to a convex set is convex,
  // the radius linear): ternary search for its minimum, then allow for the remaining interval
  // with g's Lipschitz constant |b - a| + |radius_b - radius_a|.
  const auto g = [&](double s) {
    return gap(cone, bound.a + s * (bound.b - bound.a),
               bound.radius_a + s * (bound.radius_b - bound.radius_a));
  };
  if (g(0.0) <= 0.0 || g(1.0) <= 0.0) return true;
  double lo = 0.0, hi = 1.0;
  for (int i = 0; i < 40; ++i) {
    const double m1 = lo + (hi - lo) / 3.0, m2 = hi - (hi - lo) / 3.0;
    const double g1 = g(m1), g2 = g(m2);
    if (g1 <= 0.0 || g2 <= 0.0) return true;
    if (g1 <= g2)
      hi = m2;
    else
      lo = m1;
  }
  const double lipschitz =
      glm::length(bound.b - bound.a) + std::fabs(bound.radius_b - bound.radius_a);
  const double best = std::min({g(lo), g(hi), g(0.5 * (lo + hi)), g(0.0), g(1.0)});
  return best - lipschitz * (hi - lo) <= 0.0;
}

}  // namespace shadowcts::softtile
