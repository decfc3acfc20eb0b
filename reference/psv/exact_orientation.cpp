#include "reference/psv/exact_orientation.h"

#include <cmath>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Exact_rational.h>

namespace shadowcts::psv {
namespace {

using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using Rational = CGAL::Exact_rational;

double norm1(const glm::dvec3& v) {
  return std::fabs(v.x) + std::fabs(v.y) + std::fabs(v.z);
}

}  // namespace

int orientation_sign(const glm::dvec3& p, const glm::dvec3& q, const glm::dvec3& r,
                     const glm::dvec3& s) {
  const auto point = [](const glm::dvec3& v) { return Epick::Point_3(v.x, v.y, v.z); };
  return int(CGAL::orientation(point(p), point(q), point(r), point(s)));
}

int direction_orientation_sign(const glm::dvec3& a, const glm::dvec3& b,
                               const glm::dvec3& direction, const glm::dvec3& s) {
  // det[u, d, w] = u . (d x w). Each difference and product rounds once (relative error 2^-53
  // each), so the computed value is within a few 2^-52 |u|_1 |d|_1 |w|_1 of the exact one; 2^-44
  // leaves a wide margin.
  const glm::dvec3 u = b - a, w = s - a;
  const glm::dvec3 d = direction;
  const double det =
      u.x * (d.y * w.z - d.z * w.y) - u.y * (d.x * w.z - d.z * w.x) + u.z * (d.x * w.y - d.y * w.x);
  const double bound = 0x1p-44 * norm1(u) * norm1(d) * norm1(w);
  if (det > bound) return 1;
  if (det < -bound) return -1;
  const Rational ux = Rational(b.x) - Rational(a.x), uy = Rational(b.y) - Rational(a.y),
                 uz = Rational(b.z) - Rational(a.z);
  const Rational wx = Rational(s.x) - Rational(a.x), wy = Rational(s.y) - Rational(a.y),
                 wz = Rational(s.z) - Rational(a.z);
  const Rational dx(d.x), dy(d.y), dz(d.z);
  const Rational exact =
      ux * (dy * wz - dz * wy) - uy * (dx * wz - dz * wx) + uz * (dx * wy - dy * wx);
  return int(CGAL::sign(exact));
}

}  // namespace shadowcts::psv
