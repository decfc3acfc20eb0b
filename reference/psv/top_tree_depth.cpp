#include "reference/psv/top_tree_depth.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "shadowcts/float_rounding.h"
#include "shadowcts/geometry/plane_filter.h"

namespace shadowcts::psv {
namespace {

double norm1(const glm::dvec3& v) {
  return std::fabs(v.x) + std::fabs(v.y) + std::fabs(v.z);
}
double max_abs(const glm::dvec3& v) {
  return std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
}

// Distance from q to the segment [a, a + e]. The clamped parameter's rounding moves the foot
// along the segment by at most a few 2^-52 |q - a|, and the distance is 1-Lipschitz in the foot.
double segment_distance(const glm::dvec3& q, const glm::dvec3& a, const glm::dvec3& e) {
  const double length2 = glm::dot(e, e);
  const double t = length2 > 0.0 ? std::clamp(glm::dot(q - a, e) / length2, 0.0, 1.0) : 0.0;
  return glm::length(q - (a + t * e));
}

// Point-light depth: the closest point of the triangle to L is the foot of L on its plane when
// that foot lies inside the triangle, and otherwise lies on the boundary (the distance splits as
// plane distance^2 + in-plane distance^2). The plane distance is a lower bound in every case, so
// the branch only has to be sure of "outside" before using the edge distances.
double point_light_triangle_distance_lower_bound(const glm::dvec3& light, const glm::dvec3 v[3]) {
  double m = max_abs(light);
  for (int i = 0; i < 3; ++i) m = std::max(m, max_abs(v[i]));
  // Error of a double cross product of differences of the inputs: a few 2^-52 (2 m)^2 per
  // component; 2^-44 m^2 bounds it with room.
  const double normal_error = 0x1p-44 * m * m;
  const glm::dvec3 normal = glm::cross(v[1] - v[0], v[2] - v[0]);
  const double normal_length = glm::length(normal);
  bool surely_outside = false;
  for (int k = 0; k < 3; ++k) {
    const glm::dvec3 edge = v[(k + 1) % 3] - v[k];
    const glm::dvec3 to_light = light - v[k];
    // Negative when the foot of L lies outside edge k (the plane through the edge, normal to
    // the triangle).
    const double inside = glm::dot(glm::cross(edge, to_light), normal);
    const double error = norm1(edge) * norm1(to_light) * (norm1(normal) * 0x1p-44 + normal_error);
    if (inside < -error) surely_outside = true;
  }
  double edge_distance = INFINITY;
  for (int k = 0; k < 3; ++k)
    edge_distance = std::min(edge_distance, segment_distance(light, v[k], v[(k + 1) % 3] - v[k]));
  const double distance_error = 0x1p-40 * m;
  if (surely_outside) return edge_distance - distance_error;
  if (!(normal_length > 0.0)) return 0.0;
  const glm::dvec3 to_light = light - v[0];
  const double numerator = std::fabs(glm::dot(normal, to_light)) -
                           norm1(to_light) * (normal_error + 0x1p-44 * norm1(normal));
  const double plane_distance =
      std::max(0.0, numerator) / (normal_length + 2.0 * normal_error + 0x1p-44 * normal_length);
  return std::min(plane_distance, edge_distance) - distance_error;
}

}  // namespace

float triangle_light_depth(const HardShadowLight& light, const Triangle& t) {
  const glm::dvec3 v[3] = {glm::dvec3(t.v0), glm::dvec3(t.v1), glm::dvec3(t.v2)};
  if (light.directional) {
    // -d . v is linear: its minimum over the triangle is at a vertex. Each dot product of float
    // values rounds three times: 2^-50 of the absolute terms bounds the error.
    double depth = INFINITY;
    for (const glm::dvec3& x : v) {
      const double error =
          0x1p-50 * (std::fabs(light.direction.x * x.x) + std::fabs(light.direction.y * x.y) +
                     std::fabs(light.direction.z * x.z));
      depth = std::min(depth, -glm::dot(light.direction, x) - error);
    }
    return float_below(depth);
  }
  return float_below(std::max(0.0, point_light_triangle_distance_lower_bound(light.position, v)));
}

double sample_light_depth(const HardShadowLight& light, const glm::dvec3& p) {
  return geometry::sample_light_depth(light.directional,
                                      light.directional ? light.direction : light.position, p);
}

}  // namespace shadowcts::psv
