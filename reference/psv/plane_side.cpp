#include "reference/psv/plane_side.h"

#include <cmath>
#include <utility>

#include <glm/geometric.hpp>

#include "shadowcts/geometry/exact_orientation.h"

namespace shadowcts::psv {
namespace {

glm::dvec3 vertex(const Triangle& t, int i) {
  return glm::dvec3(i == 0 ? t.v0 : (i == 1 ? t.v1 : t.v2));
}

bool lexicographically_less(const glm::dvec3& a, const glm::dvec3& b) {
  if (a.x != b.x) return a.x < b.x;
  if (a.y != b.y) return a.y < b.y;
  return a.z < b.z;
}

void store_plane(TopNode& node, const glm::dvec3& normal, double offset, int orientation) {
  // Negation is exact and rounding is symmetric, so opposite orientations give opposite bits.
  node.plane = {float(orientation * normal.x), float(orientation * normal.y),
                float(orientation * normal.z), float(orientation * offset)};
}

}  // namespace

PlaneSide::PlaneSide(const HardShadowLight& light, const std::vector<Triangle>& triangles,
                     double scene_bound)
    : light_(light),
      triangles_(triangles),
      filter_(geometry::make_plane_filter(light.directional, light.direction, scene_bound)) {}

int PlaneSide::light_side(const Triangle& t) const {
  const glm::dvec3 a = vertex(t, 0), b = vertex(t, 1), c = vertex(t, 2);
  if (!light_.directional) return geometry::orientation(a, b, c, light_.position);
  return geometry::orientation_towards(a, b, c, light_.direction);
}

void PlaneSide::make_volume_planes(std::uint32_t triangle, TopNode* first,
                                   VolumeSource& source) const {
  const Triangle& t = triangles_[triangle];
  const glm::dvec3 v[3] = {vertex(t, 0), vertex(t, 1), vertex(t, 2)};
  for (int k = 0; k < 3; ++k) {
    int lo = k, hi = (k + 1) % 3;
    if (lexicographically_less(v[hi], v[lo])) std::swap(lo, hi);
    const glm::dvec3& third = v[(k + 2) % 3];
    glm::dvec3 normal;
    double offset;
    int third_side;
    if (!light_.directional) {
      // Plane through the light and the edge: n . (s - L) = det[lo - L, hi - L, s - L].
      normal = glm::cross(v[lo] - light_.position, v[hi] - light_.position);
      offset = -glm::dot(normal, light_.position);
      third_side = geometry::orientation(light_.position, v[lo], v[hi], third);
    } else {
      // Plane through the edge, parallel to the light: n . (s - lo) = det[hi - lo, d, s - lo].
      normal = glm::cross(v[hi] - v[lo], light_.direction);
      offset = -glm::dot(normal, v[lo]);
      // det[hi - lo, d, s - lo] = -det[hi - lo, s - lo, d].
      third_side = -geometry::orientation_towards(v[lo], v[hi], third, light_.direction);
    }
    // The triangle (and so its volume) lies on the negative side.
    const int orientation = third_side > 0 ? -1 : 1;
    source.edge[std::size_t(k)] = {std::uint8_t(lo), std::uint8_t(hi)};
    source.orientation[std::size_t(k)] = std::int8_t(orientation);
    store_plane(first[k], normal, offset, orientation);
    first[k].wedge = 0.0f;
  }
  // Capping plane: the light on its positive side, the shadow behind it on the negative side.
  const glm::dvec3 normal = glm::cross(v[1] - v[0], v[2] - v[0]);
  const int orientation = light_side(t);
  source.orientation[capping_plane] = std::int8_t(orientation);
  store_plane(first[capping_plane], normal, -glm::dot(normal, v[0]), orientation);
  first[capping_plane].wedge = INFINITY;
}

double PlaneSide::value(const TopNode& node, const glm::dvec3& p) const {
  return geometry::plane_value(node.plane.data(), p);
}

double PlaneSide::error_bound(const TopNode& node, bool capping, const glm::dvec3& p) const {
  return geometry::plane_error_bound(filter_, node.plane.data(), capping, p);
}

int PlaneSide::side(const TopTree& tree, std::uint32_t node, const glm::dvec3& p) const {
  const TopNode& n = tree.nodes[node];
  const double v = value(n, p);
  const double bound = error_bound(n, is_capping_node(node), p);
  if (v > bound) return 1;
  if (v < -bound) return -1;
  exact_fallbacks_.fetch_add(1, std::memory_order_relaxed);
  return exact_side(tree, node, p);
}

int PlaneSide::exact_side(const TopTree& tree, std::uint32_t node, const glm::dvec3& p) const {
  const Triangle& t = triangles_[volume_triangle(tree, node)];
  const glm::dvec3 vertices[3] = {vertex(t, 0), vertex(t, 1), vertex(t, 2)};
  return exact_side(tree.sources[volume_of(node)], node % nodes_per_volume, vertices, p);
}

int PlaneSide::exact_side(const VolumeSource& source, std::uint32_t k,
                          const glm::dvec3 (&vertices)[3], const glm::dvec3& p) const {
  if (k == capping_plane)
    return source.orientation[k] * geometry::orientation(vertices[0], vertices[1], vertices[2], p);
  const glm::dvec3 lo = vertices[source.edge[k][0]], hi = vertices[source.edge[k][1]];
  const int sign = light_.directional ? -geometry::orientation_towards(lo, hi, p, light_.direction)
                                      : geometry::orientation(light_.position, lo, hi, p);
  return source.orientation[k] * sign;
}

}  // namespace shadowcts::psv
