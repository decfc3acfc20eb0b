#include "reference/metric/normal_cones.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "reference/metric/angular_distance.h"

namespace shadowcts::metric {
namespace {

// Signed volumes smaller than this fraction of the bounding box's volume leave the orientation
// undecided (a flat or self-cancelling "closed" mesh).
constexpr double smallest_volume_fraction = 1e-9;

// Separates the cone test from the rounding of its angles (each within ~1e-15 radians).
constexpr double angle_margin = 1e-9;

}  // namespace

std::vector<int> closed_mesh_orientations(const Case& c) {
  std::vector<double> volume(c.meshes.size(), 0.0);
  std::vector<glm::dvec3> lo(c.meshes.size(), glm::dvec3(INFINITY)),
      hi(c.meshes.size(), glm::dvec3(-INFINITY));
  std::vector<glm::dvec3> origin(c.meshes.size(), glm::dvec3(0.0));
  std::vector<bool> has_origin(c.meshes.size(), false);
  for (const Triangle& t : c.triangles) {
    if (!c.meshes[t.mesh].closed) continue;
    // Volumes relative to a vertex of the mesh keep the determinants small.
    if (!has_origin[t.mesh]) origin[t.mesh] = glm::dvec3(t.v0), has_origin[t.mesh] = true;
    const glm::dvec3 a = glm::dvec3(t.v0) - origin[t.mesh], b = glm::dvec3(t.v1) - origin[t.mesh],
                     d = glm::dvec3(t.v2) - origin[t.mesh];
    volume[t.mesh] += glm::dot(a, glm::cross(b, d)) / 6.0;
    for (const glm::vec3& v : {t.v0, t.v1, t.v2}) {
      lo[t.mesh] = glm::min(lo[t.mesh], glm::dvec3(v));
      hi[t.mesh] = glm::max(hi[t.mesh], glm::dvec3(v));
    }
  }
  std::vector<int> orientation(c.meshes.size(), 0);
  for (std::size_t m = 0; m < c.meshes.size(); ++m) {
    if (!c.meshes[m].closed || !has_origin[m]) continue;
    const glm::dvec3 size = hi[m] - lo[m];
    const double box_volume = size.x * size.y * size.z;
    if (std::fabs(volume[m]) <= smallest_volume_fraction * box_volume) continue;
    orientation[m] = volume[m] > 0.0 ? 1 : -1;
  }
  return orientation;
}

NormalCone normal_cone(const Case& c, std::span<const std::uint32_t> triangles,
                       const std::vector<int>& orientations) {
  const int orientation = orientations[c.triangles[triangles[0]].mesh];
  std::vector<glm::dvec3> normals;
  std::vector<double> direction_error;  // bound on the angle between computed and exact normal
  glm::dvec3 sum(0.0);
  for (std::uint32_t i : triangles) {
    const Triangle& t = c.triangles[i];
    const glm::dvec3 e1 = glm::dvec3(t.v1) - glm::dvec3(t.v0),
                     e2 = glm::dvec3(t.v2) - glm::dvec3(t.v0);
    const glm::dvec3 n = glm::cross(e1, e2);
    const double length = glm::length(n);
    // Each cross-product component is one rounded difference of two products bounded by
    // |e1| |e2|: its error is a few 2^-53 |e1| |e2|, a large angle only for slivers. A sliver whose
    // rounded normal vanishes has an unknown direction, so the cone opens fully.
    normals.push_back(length > 0.0 ? n / length * double(orientation >= 0 ? 1 : -1)
                                   : glm::dvec3(0.0));
    direction_error.push_back(length > 0.0 ? 1e-15 * glm::length(e1) * glm::length(e2) / length
                                           : std::numbers::pi);
    sum += normals.back();
  }
  NormalCone cone;
  cone.cullable = orientation != 0;
  const double sum_length = glm::length(sum);
  if (!(sum_length > 0.0)) {
    cone.half_angle = std::numbers::pi;
    return cone;
  }
  cone.axis = sum / sum_length;
  for (std::size_t i = 0; i < normals.size(); ++i)
    cone.half_angle = std::min(
        std::numbers::pi,
        std::max(cone.half_angle, angle_between(cone.axis, normals[i]) + direction_error[i]));
  return cone;
}

bool faces_away_from_light(const NormalCone& cone, const glm::dvec3& centre, double reach,
                           bool point_light, const glm::dvec3& light) {
  if (!cone.cullable || cone.half_angle >= std::numbers::pi / 2) return false;
  glm::dvec3 towards_light = light;
  double spread = 0.0;  // half angle of the directions from the cluster's points to the light
  if (point_light) {
    towards_light = light - centre;
    const double distance = glm::length(towards_light);
    if (!(distance > reach)) return false;
    spread = std::asin(reach / distance);
  }
  // Every normal is within half_angle of the axis and every direction to the light within spread
  // of towards_light, so all their angles exceed angle(axis, towards_light) - half_angle - spread.
  return angle_between(cone.axis, towards_light) - cone.half_angle - spread >
         std::numbers::pi / 2 + angle_margin;
}

}  // namespace shadowcts::metric
