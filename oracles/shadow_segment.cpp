#include "oracles/shadow_segment.h"

namespace shadowcts {
namespace {

// (a.x b.x + a.y b.y) + a.z b.z: error at most gamma_3 sum |a_i b_i| (gamma_3 = 3u / (1 - 3u),
// u = 2^-53), also if the compiler contracts to FMA.
double dot(const glm::dvec3& a, const glm::dvec3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

glm::dvec3 cross(const glm::dvec3& a, const glm::dvec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// Separating axis a (any double vector: the argument holds for the computed axis as it is):
// the inflated query projects onto [q_min - t |a|_1, q_max + t |a|_1], the triangle onto
// [t_min, t_max]. They are disjoint, so the triangle misses the inflated query, when the exact
// gap g = max(t_min - q_max, q_min - t_max) exceeds t |a|_1.
//
// Error bound: every projection is a dot product with points of |coordinate| <= bound, so it is
// off by at most gamma_3 |a|_1 bound; the gap adds one more rounding, u |g|. Hence
// g >= gap - err with err = 2^-50 |a|_1 bound + 2^-52 |gap| (+ 2^-1000 for underflow), since
// 2 gamma_3 < 0.75 * 2^-50. The result (gap - err) / |a|_1, shrunk by (1 - 2^-49) to cover the
// rounding of |a|_1 and of the division, is then a valid lower bound on the separating inflation.
//
// For a ray the projection is a half-line; its side is the sign of a . d, trusted only when
// |a . d| exceeds its own error bound 2^-50 sum |a_i d_i|.
double axis_separation(const ShadowSegment& s, const glm::dvec3& a, const glm::dvec3& v0,
                       const glm::dvec3& v1, const glm::dvec3& v2) {
  const double norm1 = std::fabs(a.x) + std::fabs(a.y) + std::fabs(a.z);
  if (!(norm1 > 0.0) || !std::isfinite(norm1)) return 0.0;
  const double p0 = dot(a, v0), p1 = dot(a, v1), p2 = dot(a, v2);
  const double tri_min = std::min({p0, p1, p2});
  const double tri_max = std::max({p0, p1, p2});
  const double q_origin = dot(a, s.origin);
  double gap;
  if (!s.is_ray) {
    const double q_end = dot(a, s.end);
    gap = std::max(tri_min - std::max(q_origin, q_end), std::min(q_origin, q_end) - tri_max);
  } else {
    const double along = dot(a, s.direction);
    const double along_error =
        0x1p-50 * (std::fabs(a.x * s.direction.x) + std::fabs(a.y * s.direction.y) +
                   std::fabs(a.z * s.direction.z)) +
        0x1p-1000;
    if (along > along_error) {
      gap = q_origin - tri_max;  // the ray projects onto [q_origin, +inf)
    } else if (along < -along_error) {
      gap = tri_min - q_origin;  // (-inf, q_origin]
    } else {
      return 0.0;  // sign unknown: the projection may be the whole line
    }
  }
  const double error = 0x1p-50 * norm1 * s.bound + 0x1p-52 * std::fabs(gap) + 0x1p-1000;
  if (!(gap > error)) return 0.0;
  return (gap - error) / norm1 * (1.0 - 0x1p-49);
}

}  // namespace

double separation_inflation(const ShadowSegment& s, const glm::dvec3& v0, const glm::dvec3& v1,
                            const glm::dvec3& v2, double give_up_above) {
  // Any set of axes gives a valid bound (a separating axis proves separation); the more of the
  // separating-axis theorem's axes for a triangle against the inflated segment (a zonotope with
  // edge directions e_x, e_y, e_z, d), the tighter. Cheap and decisive ones first.
  double best = 0.0;
  auto consider = [&](const glm::dvec3& axis) {
    best = std::max(best, axis_separation(s, axis, v0, v1, v2));
    return best > give_up_above;
  };
  const glm::dvec3 unit[3] = {{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}};
  for (const glm::dvec3& e : unit)
    if (consider(e)) return best;
  const glm::dvec3& d = s.direction;
  for (const glm::dvec3& e : unit)
    if (consider(cross(d, e))) return best;
  const glm::dvec3 edges[3] = {v1 - v0, v2 - v1, v0 - v2};
  if (consider(cross(edges[0], v2 - v0))) return best;  // the triangle's normal
  for (const glm::dvec3& f : edges)
    if (consider(cross(f, d))) return best;
  for (const glm::dvec3& f : edges)
    for (const glm::dvec3& e : unit)
      if (consider(cross(f, e))) return best;
  return best;
}

}  // namespace shadowcts
