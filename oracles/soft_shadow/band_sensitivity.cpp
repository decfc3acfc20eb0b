#include "oracles/soft_shadow/band_sensitivity.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "oracles/soft_shadow/disk_polygon_area.h"

namespace shadowcts {

double triangle_band_sensitivity(const SunDiskFrame& frame, const glm::dvec3& p,
                                 const std::array<glm::dvec3, 3>& v, double distance, double move) {
  const double t = frame.tan_radius;
  const double nearest_height = (distance - move) * std::cos(frame.angular_radius) - move;
  if (!(nearest_height > 0.0)) return 1.0;
  const double m = move * (1.0 + t) / (t * nearest_height);
  if (!(m < 1.0)) return 1.0;
  // Clipped to a square that contains the disk of radius 1 + m < 2, so the square's own sides add
  // no length inside it.
  const DiskPolygon polygon = project_triangle(frame, p, v, FrontProjection::clipped, 3.0);
  // No area at p (behind, or edge-on): a moved projection can still appear; bound its boundary by
  // the perimeter of the disk of radius 1 + m, the longest a convex set inside it can have.
  const double length = polygon.count > 0 ? boundary_length_in_disk(polygon, 1.0 + m)
                                          : 2.0 * std::numbers::pi * (1.0 + m);
  if (length == 0.0) return 0.0;
  const double bound = (2.0 * m * length + std::numbers::pi * m * m) / std::numbers::pi;
  return std::min(1.0, bound * (1.0 + 1e-6));  // covers the double rounding of the terms
}

double caster_band_sensitivity(const SunDiskFrame& frame, const glm::dvec3& p,
                               const std::array<glm::dvec3, 3>& v, double angle, double move) {
  const double distance = distance_to_triangle(p, v);
  const double off_cone =
      distance * std::sin(std::min(angle - frame.angular_radius, std::numbers::pi / 2));
  if (!(off_cone <= move * (1.0 + 1e-9))) return 0.0;
  return triangle_band_sensitivity(frame, p, v, distance, move);
}

double sample_band_sensitivity(const Case& c, const SunDiskFrame& frame,
                               const LightConeBvh& casters, const ViewSample& sample, double move) {
  const glm::dvec3 p(sample.position);
  double sensitivity = 0.0;
  casters.visit(
      LightCone{p, frame.direction, frame.angular_radius}, move, [&](std::uint32_t index) {
        if (index == sample.receiver || sensitivity >= 1.0) return;
        const Triangle& t = c.triangles[index];
        const std::array<glm::dvec3, 3> v{glm::dvec3(t.v0), glm::dvec3(t.v1), glm::dvec3(t.v2)};
        const std::array<glm::dvec3, 3> w{v[0] - p, v[1] - p, v[2] - p};
        sensitivity = std::min(
            1.0, sensitivity + caster_band_sensitivity(
                                   frame, p, v, angle_to_triangle(frame.direction, w), move));
      });
  return sensitivity;
}

}  // namespace shadowcts
