#include "oracles/soft_shadow/disk_polygon_area.h"

#include <algorithm>
#include <cmath>

namespace shadowcts {
namespace {

double cross(const glm::dvec2& a, const glm::dvec2& b) {
  return a.x * b.y - a.y * b.x;
}

// The parameters t0 <= t1 where a + t (b - a) meets the circle of `radius`; false if the line
// misses it (or a == b).
bool circle_crossings(const glm::dvec2& a, const glm::dvec2& b, double radius, double& t0,
                      double& t1) {
  const glm::dvec2 e = b - a;
  const double qa = e.x * e.x + e.y * e.y;
  if (qa == 0.0) return false;
  const double qb = a.x * e.x + a.y * e.y;  // half of the linear coefficient
  const double qc = a.x * a.x + a.y * a.y - radius * radius;
  const double discriminant = qb * qb - qa * qc;
  if (discriminant <= 0.0) return false;
  const double root = std::sqrt(discriminant);
  // Citardauq form for the root that would cancel.
  const double q = qb >= 0.0 ? -(qb + root) : -(qb - root);
  double r0 = q / qa, r1 = q != 0.0 ? qc / q : r0;
  if (r0 > r1) std::swap(r0, r1);
  t0 = r0;
  t1 = r1;
  return true;
}

// Signed area of triangle(origin, a, b) ∩ unit disk.
double signed_fan_area(const glm::dvec2& a, const glm::dvec2& b) {
  const auto sector = [](const glm::dvec2& u, const glm::dvec2& v) {
    return 0.5 * std::atan2(cross(u, v), u.x * v.x + u.y * v.y);
  };
  double t0 = 0.0, t1 = 0.0;
  if (!circle_crossings(a, b, 1.0, t0, t1)) {
    // The segment's line misses the open disk: the fan is a sector, unless both ends are inside
    // (only possible for a degenerate segment).
    if (a.x * a.x + a.y * a.y <= 1.0 && b.x * b.x + b.y * b.y <= 1.0) return 0.5 * cross(a, b);
    return sector(a, b);
  }
  const double s = std::clamp(t0, 0.0, 1.0), e = std::clamp(t1, 0.0, 1.0);
  if (s >= e) return sector(a, b);  // the segment lies outside the disk
  const glm::dvec2 p = a + s * (b - a), q = a + e * (b - a);
  return sector(a, p) + 0.5 * cross(p, q) + sector(q, b);
}

}  // namespace

double unit_disk_intersection_area(const DiskPolygon& polygon) {
  double sum = 0.0;
  for (int i = 0; i < polygon.count; ++i)
    sum += signed_fan_area(polygon.corners[i], polygon.corners[(i + 1) % polygon.count]);
  return std::fabs(sum);
}

double boundary_length_in_disk(const DiskPolygon& polygon, double radius) {
  double length = 0.0;
  for (int i = 0; i < polygon.count; ++i) {
    const glm::dvec2& a = polygon.corners[i];
    const glm::dvec2& b = polygon.corners[(i + 1) % polygon.count];
    double t0 = 0.0, t1 = 0.0;
    if (!circle_crossings(a, b, radius, t0, t1)) continue;
    const double s = std::clamp(t0, 0.0, 1.0), e = std::clamp(t1, 0.0, 1.0);
    if (e > s) length += (e - s) * std::hypot(b.x - a.x, b.y - a.y);
  }
  return length;
}

}  // namespace shadowcts
