#include "oracles/soft_shadow/sun_disk_projection.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "oracles/exact_segment_triangle.h"
#include "shadowcts/errors.h"

namespace shadowcts {
namespace {

// Slack that turns the double evaluations below into conservative bounds: their relative rounding
// error is a few 1e-16, six orders of magnitude below it.
constexpr double angle_slack = 1e-9;
constexpr double relative_slack = 1e-12;

using Homogeneous = glm::dvec3;  // (X * z, Y * z, z) in disk units

// Keeps the part of `polygon` where a X + b Y + c >= 0 (Sutherland-Hodgman, one plane).
void clip(DiskPolygon& polygon, const glm::dvec3& line) {
  DiskPolygon out;
  auto value = [&](const glm::dvec2& q) { return line.x * q.x + line.y * q.y + line.z; };
  for (int i = 0; i < polygon.count; ++i) {
    const glm::dvec2& a = polygon.corners[i];
    const glm::dvec2& b = polygon.corners[(i + 1) % polygon.count];
    const double fa = value(a), fb = value(b);
    if (fa >= 0.0) out.corners[out.count++] = a;
    if ((fa >= 0.0) != (fb >= 0.0)) {
      const double t = fa / (fa - fb);
      out.corners[out.count++] = a + t * (b - a);
    }
  }
  polygon = out.count >= 3 ? out : DiskPolygon{};
}

double angle_between(const glm::dvec3& a, const glm::dvec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

}  // namespace

DiskPolygon project_triangle(const SunDiskFrame& frame, const glm::dvec3& p,
                             const std::array<glm::dvec3, 3>& v, FrontProjection front,
                             double half_width) {
  std::array<Homogeneous, 3> h;
  bool all_front = true, all_behind = true;
  for (int i = 0; i < 3; ++i) {
    const glm::dvec3 w = v[i] - p;
    h[i] = {glm::dot(w, frame.x_axis) / frame.tan_radius,
            glm::dot(w, frame.y_axis) / frame.tan_radius, glm::dot(w, frame.direction)};
    all_front = all_front && h[i].z > 0.0;
    all_behind = all_behind && h[i].z <= 0.0;
  }
  DiskPolygon polygon;
  if (all_behind) return polygon;
  if (all_front && front == FrontProjection::vertices) {
    for (int i = 0; i < 3; ++i) polygon.corners[i] = {h[i].x / h[i].z, h[i].y / h[i].z};
    polygon.count = 3;
    return polygon;
  }
  // h is v - p in a scaled rotation of light space, so det(h0, h1, h2) has the sign of the exact
  // orientation of (p, v0, v1, v2) times the light frame's handedness. Decided exactly: from a
  // caster in p's own plane (a coplanar neighbour of the receiver) the rounded h have a det of
  // either sign, whose "cone" is then a half-space of directions (or its part beside a shared
  // edge through p) instead of the edge-on triangle's no area.
  const int side = exact_orientation(p, v[0], v[1], v[2]);
  if (side == 0) return polygon;  // seen edge-on: no area
  const double handedness =
      glm::dot(glm::cross(frame.x_axis, frame.y_axis), frame.direction) > 0.0 ? 1.0 : -1.0;
  const double sign = double(side) * handedness;
  polygon.corners[0] = {-half_width, -half_width};
  polygon.corners[1] = {half_width, -half_width};
  polygon.corners[2] = {half_width, half_width};
  polygon.corners[3] = {-half_width, half_width};
  polygon.count = 4;
  for (int i = 0; i < 3 && polygon.count > 0; ++i)
    clip(polygon, sign * glm::cross(h[i], h[(i + 1) % 3]));
  return polygon;
}

double angle_to_triangle(const glm::dvec3& d, const std::array<glm::dvec3, 3>& w) {
  std::array<glm::dvec3, 3> u;
  for (int i = 0; i < 3; ++i) {
    const double length = glm::length(w[i]);
    if (length == 0.0) return 0.0;
    u[i] = w[i] / length;
  }
  const double det = glm::dot(u[0], glm::cross(u[1], u[2]));
  if (det != 0.0) {
    const double s = det > 0.0 ? 1.0 : -1.0;
    bool inside = true;
    for (int i = 0; i < 3; ++i)
      inside = inside && s * glm::dot(glm::cross(u[i], u[(i + 1) % 3]), d) >= 0.0;
    if (inside) return 0.0;
  }
  double best = std::numbers::pi;
  for (int i = 0; i < 3; ++i) best = std::min(best, angle_between(d, u[i]));
  for (int i = 0; i < 3; ++i) {
    const glm::dvec3& a = u[i];
    const glm::dvec3& b = u[(i + 1) % 3];
    const glm::dvec3 n = glm::cross(a, b);
    const double n_length = glm::length(n);
    if (n_length < 1e-12) {
      // Nearly antiparallel directions: the edge passes (almost) through p.
      if (glm::dot(a, b) < 0.0) return 0.0;
      continue;  // (nearly) the same direction: the endpoints decide
    }
    const glm::dvec3 normal = n / n_length;
    const glm::dvec3 in_plane = d - glm::dot(d, normal) * normal;
    // The nearest point of the great circle lies on the arc from a to b.
    if (glm::dot(glm::cross(a, in_plane), n) >= 0.0 && glm::dot(glm::cross(in_plane, b), n) >= 0.0)
      best = std::min(best, std::atan2(std::fabs(glm::dot(d, normal)), glm::length(in_plane)));
  }
  return std::max(0.0, best - angle_slack);
}

double distance_to_triangle(const glm::dvec3& p, const std::array<glm::dvec3, 3>& v) {
  const double scale = glm::length(p) + glm::length(v[0]) + glm::length(v[1]) + glm::length(v[2]);
  const auto lower = [&](double distance) {
    return std::max(0.0, distance * (1.0 - relative_slack) - relative_slack * scale);
  };
  // Edge i runs from v_i along e_i; to_p_i = p - v_i.
  const std::array<glm::dvec3, 3> e{v[1] - v[0], v[2] - v[1], v[0] - v[2]};
  const std::array<glm::dvec3, 3> to_p{p - v[0], p - v[1], p - v[2]};
  // The edges: the point of each segment nearest p, from a clamped parameter (an error in it moves
  // the point along the segment, which lengthens |p - q| by far less than the slack).
  double edges = HUGE_VAL;
  for (int i = 0; i < 3; ++i) {
    const double length2 = glm::dot(e[i], e[i]);
    const double t = length2 > 0.0 ? std::clamp(glm::dot(to_p[i], e[i]) / length2, 0.0, 1.0) : 0.0;
    edges = std::min(edges, glm::length(p - (v[i] + t * e[i])));
  }
  // Where p's projection onto the plane lies outside the triangle, the nearest point is on an
  // edge. Decided only where certain: s_i = (e_i x to_p_i) . n is negative for p beyond edge i,
  // and its rounding error stays below 1e-12 |e_i| |to_p_i| |ab| |ac| (a few 1e-16 of those
  // magnitudes). A needle or sliver makes n and the s_i ill-conditioned (the region tests of the
  // closest-point method then picked a far vertex for a point 4 units from a needle's edge);
  // there p may lie over the triangle, and the plane's distance, never more than the triangle's,
  // is the bound. (ac = -e_2 exactly: a rounded difference changes sign with its operands.)
  const glm::dvec3 n = glm::cross(e[0], -e[2]);
  const double n_length = glm::length(n);
  const double magnitude = glm::length(e[0]) * glm::length(e[2]);
  if (!(n_length > 0.0)) return lower(edges);  // no plane: the triangle is its edges
  for (int i = 0; i < 3; ++i)
    if (glm::dot(glm::cross(e[i], to_p[i]), n) <
        -1e-12 * glm::length(e[i]) * glm::length(to_p[i]) * magnitude)
      return lower(edges);
  // |n . (p - a)| / |n| with n exact: the numerator less, the denominator more than what an
  // error of 1e-12 |ab| |ac| in n can change.
  const double plane =
      (std::fabs(glm::dot(n, to_p[0])) - 1e-12 * magnitude * glm::length(to_p[0])) /
      (n_length + 1e-12 * magnitude);
  return lower(std::min(edges, std::max(0.0, plane)));
}

}  // namespace shadowcts
