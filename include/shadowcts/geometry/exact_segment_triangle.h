#pragma once
// Exact test of a closed shadow segment (point light) or closed shadow ray (directional light)
// against a closed triangle, for host and device: only orientation signs of the float inputs
// (exact_orientation.h), never a constructed plane or intersection point. It is what an
// algorithm's exact path decides with; the oracles decide with CGAL, independently.
//
// - The segment (ray) crosses the triangle's plane at one point: it meets the triangle iff the
//   three volumes [p, q, a, b], [p, q, b, c], [p, q, c, a] do not have opposite signs (the line
//   passes through the closed triangle), for a segment only where p and q are not strictly on one
//   side of the plane.
// - It lies in the plane: a 2D test in the projection along an axis the plane is not parallel to
//   (an endpoint inside the triangle, or a crossing with one of its edges).
#include <glm/vec3.hpp>

#include "shadowcts/geometry/exact_orientation.h"
#include "shadowcts/geometry/expansion.h"
#include "shadowcts/geometry/receiver_half_space.h"
#include "shadowcts/host_device.h"

namespace shadowcts::geometry {
SHADOWCTS_GEOMETRY_ABI_BEGIN

namespace detail {

// An axis along which the triangle's projection has non-zero area; -1 when it has zero area.
SHADOWCTS_HD inline int projection_axis(const glm::dvec3& a, const glm::dvec3& b,
                                        const glm::dvec3& c) {
  for (int k = 0; k < 3; ++k) {
    glm::dvec3 axis(0.0);
    axis[k] = 1.0;
    if (orientation_towards(a, b, c, axis) != 0) return k;
  }
  return -1;
}

// Exact sign of the 2D cross product u_i v_j - u_j v_i with u = x - y and v a float vector.
SHADOWCTS_HD inline int cross_sign(const glm::dvec3& x, const glm::dvec3& y, const glm::dvec3& v,
                                   int i, int j) {
  return sign(
      sum(scaled(difference(x[i], y[i]), v[j]), negated(scaled(difference(x[j], y[j]), v[i]))));
}

// Exact sign of u_i v_j - u_j v_i with u = x - y and v = z - w.
SHADOWCTS_HD inline int cross_sign(const glm::dvec3& x, const glm::dvec3& y, const glm::dvec3& z,
                                   const glm::dvec3& w, int i, int j) {
  return sign(sum(product(difference(x[i], y[i]), difference(z[j], w[j])),
                  negated(product(difference(x[j], y[j]), difference(z[i], w[i])))));
}

// Exact sign of u_i v_i + u_j v_j with u = x - y.
SHADOWCTS_HD inline int dot_sign(const glm::dvec3& x, const glm::dvec3& y, const glm::dvec3& v,
                                 int i, int j) {
  return sign(sum(scaled(difference(x[i], y[i]), v[i]), scaled(difference(x[j], y[j]), v[j])));
}

// 2D, in the projection along axis k: does the closed segment [p, q] meet the closed segment
// [a, b]?
SHADOWCTS_HD inline bool segments_meet(const glm::dvec3& p, const glm::dvec3& q,
                                       const glm::dvec3& a, const glm::dvec3& b, int k) {
  glm::dvec3 axis(0.0);
  axis[k] = 1.0;
  const int o1 = orientation_towards(p, q, a, axis), o2 = orientation_towards(p, q, b, axis);
  const int o3 = orientation_towards(a, b, p, axis), o4 = orientation_towards(a, b, q, axis);
  if (o1 != 0 || o2 != 0 || o3 != 0 || o4 != 0) return o1 * o2 <= 0 && o3 * o4 <= 0;
  // Collinear: the intervals overlap along both other axes (one of them separates distinct
  // points).
  for (int i = 0; i < 3; ++i) {
    if (i == k) continue;
    const double lo1 = p[i] < q[i] ? p[i] : q[i], hi1 = p[i] < q[i] ? q[i] : p[i];
    const double lo2 = a[i] < b[i] ? a[i] : b[i], hi2 = a[i] < b[i] ? b[i] : a[i];
    if (hi1 < lo2 || hi2 < lo1) return false;
  }
  return true;
}

// 2D, in the projection along axis k (i, j the other two): does the closed ray p + t d, t >= 0,
// meet the closed segment [a, b]? (d_i, d_j) != 0.
SHADOWCTS_HD inline bool ray_meets_segment(const glm::dvec3& p, const glm::dvec3& d,
                                           const glm::dvec3& a, const glm::dvec3& b, int i, int j) {
  // Sides of a and b of the ray's line: sign of d x (a - p) = -(a - p) x d.
  const int sa = -cross_sign(a, p, d, i, j), sb = -cross_sign(b, p, d, i, j);
  if (sa * sb > 0) return false;
  if (sa == 0 && sb == 0) return dot_sign(a, p, d, i, j) >= 0 || dot_sign(b, p, d, i, j) >= 0;
  // One crossing p + t d of the line through a and b, t = ((a - p) x (b - a)) / (d x (b - a));
  // d x (b - a) = sb - sa (as values) is not zero here.
  const int numerator = cross_sign(a, p, b, a, i, j);
  const int denominator = -cross_sign(b, a, d, i, j);
  return numerator * denominator >= 0;
}

}  // namespace detail

// Does the closed segment [p, light] meet the closed triangle (a, b, c)? False for a triangle of
// zero area.
SHADOWCTS_HD inline bool segment_meets_triangle(const glm::dvec3& p, const glm::dvec3& light,
                                                const glm::dvec3& a, const glm::dvec3& b,
                                                const glm::dvec3& c) {
  const int k = detail::projection_axis(a, b, c);
  if (k < 0) return false;
  const int sp = orientation(a, b, c, p), sl = orientation(a, b, c, light);
  if (sp * sl > 0) return false;
  if (sp != 0 || sl != 0) {
    const int u = orientation(p, light, a, b), v = orientation(p, light, b, c),
              w = orientation(p, light, c, a);
    return !((u > 0 || v > 0 || w > 0) && (u < 0 || v < 0 || w < 0));
  }
  return detail::point_in_coplanar_triangle(p, a, b, c) ||
         detail::point_in_coplanar_triangle(light, a, b, c) ||
         detail::segments_meet(p, light, a, b, k) || detail::segments_meet(p, light, b, c, k) ||
         detail::segments_meet(p, light, c, a, k);
}

// Does the closed ray p + t d, t >= 0, meet the closed triangle (a, b, c)? d != 0 (the direction
// towards a directional light). False for a triangle of zero area.
SHADOWCTS_HD inline bool ray_meets_triangle(const glm::dvec3& p, const glm::dvec3& d,
                                            const glm::dvec3& a, const glm::dvec3& b,
                                            const glm::dvec3& c) {
  const int k = detail::projection_axis(a, b, c);
  if (k < 0) return false;
  const int sp = orientation(a, b, c, p), sd = orientation_towards(a, b, c, d);
  // Along the ray the orientation changes with the sign of sd: it reaches zero iff it starts
  // there or moves towards it.
  if (sp != 0 && sp * sd >= 0) return false;
  if (sp != 0) {
    // det[p - x, (p + d) - x, ...] for the line through p with direction d: orientation_towards
    // of (x, y, p) along d is the volume [x, y, p, p + d].
    const int u = orientation_towards(a, b, p, d), v = orientation_towards(b, c, p, d),
              w = orientation_towards(c, a, p, d);
    return !((u > 0 || v > 0 || w > 0) && (u < 0 || v < 0 || w < 0));
  }
  if (sd != 0) return detail::point_in_coplanar_triangle(p, a, b, c);
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  return detail::point_in_coplanar_triangle(p, a, b, c) ||
         detail::ray_meets_segment(p, d, a, b, i, j) ||
         detail::ray_meets_segment(p, d, b, c, i, j) || detail::ray_meets_segment(p, d, c, a, i, j);
}

SHADOWCTS_GEOMETRY_ABI_END
}  // namespace shadowcts::geometry
