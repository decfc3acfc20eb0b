#pragma once
// Exact 3D orientation for double (and so float) inputs, for host and device: a filtered double
// evaluation with a certified error bound, and exact floating-point expansions where the bound
// cannot decide (expansion.h). One implementation for every algorithm and backend; the oracles
// decide the same signs with CGAL, independently.
//
// orientation(a, b, c, d) is the sign of det[b - a, c - a, d - a]: positive when d lies on the
// side the normal (b - a) x (c - a) points to. orientation_towards(a, b, c, u) is the sign of
// det[b - a, c - a, u] = ((b - a) x (c - a)) . u for a direction u.
#include <cmath>

#include <glm/vec3.hpp>

#include "shadowcts/geometry/expansion.h"
#include "shadowcts/geometry/rounded_arithmetic.h"
#include "shadowcts/host_device.h"

namespace shadowcts::geometry {
SHADOWCTS_GEOMETRY_ABI_BEGIN

namespace detail {

// The filter's bound on |computed - exact| of a 3x3 determinant whose entries were each rounded
// once (differences of inputs) and that is evaluated by minors: (7 + 56 eps) eps times the
// permanent, eps = 2^-53 (the bound of Shewchuk's orient3d stage A, derived for this evaluation
// order: entries, 2x2 minors, products, sums).
inline constexpr double orientation_error_factor = (7.0 + 56.0 * 0x1p-53) * 0x1p-53;
// Below this permanent (or where it is not finite) the double evaluation may underflow or
// overflow and the bound does not hold: the exact path decides.
inline constexpr double smallest_filtered_permanent = 0x1p-900;

SHADOWCTS_HD inline double minor2(double a, double b, double c, double d) {
  return rounded_sub(rounded_mul(a, d), rounded_mul(b, c));
}

SHADOWCTS_HD inline double abs_minor2(double a, double b, double c, double d) {
  return rounded_add(fabs(rounded_mul(a, d)), fabs(rounded_mul(b, c)));
}

// det[u; v; w] of rows u, v, w and its permanent (the same sum with absolute values).
SHADOWCTS_HD inline void filtered_determinant(const double u[3], const double v[3],
                                              const double w[3], double& det, double& permanent) {
  const double m0 = minor2(v[1], v[2], w[1], w[2]);
  const double m1 = minor2(v[0], v[2], w[0], w[2]);
  const double m2 = minor2(v[0], v[1], w[0], w[1]);
  det =
      rounded_add(rounded_sub(rounded_mul(u[0], m0), rounded_mul(u[1], m1)), rounded_mul(u[2], m2));
  permanent = rounded_add(rounded_add(rounded_mul(fabs(u[0]), abs_minor2(v[1], v[2], w[1], w[2])),
                                      rounded_mul(fabs(u[1]), abs_minor2(v[0], v[2], w[0], w[2]))),
                          rounded_mul(fabs(u[2]), abs_minor2(v[0], v[1], w[0], w[1])));
}

// A coordinate in which all three rows vanish makes the determinant exactly zero. A difference of
// doubles is zero only for equal doubles (gradual underflow), so this is exact: points sharing an
// axis-aligned plane (a flat floor's samples and triangles) skip the expansions the filter leaves
// them to.
SHADOWCTS_HD inline bool has_zero_row(const double u[3], const double v[3], const double w[3]) {
  for (int i = 0; i < 3; ++i)
    if (u[i] == 0.0 && v[i] == 0.0 && w[i] == 0.0) return true;
  return false;
}

SHADOWCTS_HD inline int certified_sign(double det, double permanent) {
  if (!(permanent >= smallest_filtered_permanent) || !(permanent < 0x1p+1000)) return 2;
  const double bound = rounded_mul(orientation_error_factor, permanent);
  if (det > bound) return 1;
  if (-det > bound) return -1;
  return 2;  // unsure
}

template <int N, int M>
SHADOWCTS_HD inline Expansion<2 * N * M> times(const Expansion<N>& a, const Expansion<M>& b) {
  return product(a, b);
}

// x0 * (y1 z2 - y2 z1) etc.: the 2x2 minor y_i z_j - y_j z_i of expansion entries.
template <int N, int M>
SHADOWCTS_HD inline Expansion<4 * N * M> exact_minor(const Expansion<N>& yi, const Expansion<N>& yj,
                                                     const Expansion<M>& zi,
                                                     const Expansion<M>& zj) {
  return sum(times(yi, zj), negated(times(yj, zi)));
}

}  // namespace detail

// The exact value of det[b - a, c - a, d - a] as an expansion.
SHADOWCTS_HD inline Expansion<192> orientation_value(const glm::dvec3& a, const glm::dvec3& b,
                                                     const glm::dvec3& c, const glm::dvec3& d) {
  Expansion<2> u[3], v[3], w[3];
  for (int i = 0; i < 3; ++i) {
    u[i] = difference(b[i], a[i]);
    v[i] = difference(c[i], a[i]);
    w[i] = difference(d[i], a[i]);
  }
  const Expansion<16> m0 = detail::exact_minor(v[1], v[2], w[1], w[2]);
  const Expansion<16> m1 = detail::exact_minor(v[0], v[2], w[0], w[2]);
  const Expansion<16> m2 = detail::exact_minor(v[0], v[1], w[0], w[1]);
  return sum(sum(product(u[0], m0), negated(product(u[1], m1))), product(u[2], m2));
}

// The exact value of det[b - a, c - a, direction] as an expansion.
SHADOWCTS_HD inline Expansion<96> orientation_towards_value(const glm::dvec3& a,
                                                            const glm::dvec3& b,
                                                            const glm::dvec3& c,
                                                            const glm::dvec3& direction) {
  Expansion<2> u[3], v[3];
  Expansion<1> w[3];
  for (int i = 0; i < 3; ++i) {
    u[i] = difference(b[i], a[i]);
    v[i] = difference(c[i], a[i]);
    w[i] = expansion_of(direction[i]);
  }
  const Expansion<8> m0 = detail::exact_minor(v[1], v[2], w[1], w[2]);
  const Expansion<8> m1 = detail::exact_minor(v[0], v[2], w[0], w[2]);
  const Expansion<8> m2 = detail::exact_minor(v[0], v[1], w[0], w[1]);
  return sum(sum(product(u[0], m0), negated(product(u[1], m1))), product(u[2], m2));
}

// Sign of det[b - a, c - a, d - a].
SHADOWCTS_HD inline int orientation(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                                    const glm::dvec3& d) {
  double u[3], v[3], w[3];
  for (int i = 0; i < 3; ++i) {
    u[i] = rounded_sub(b[i], a[i]);
    v[i] = rounded_sub(c[i], a[i]);
    w[i] = rounded_sub(d[i], a[i]);
  }
  double det = 0.0, permanent = 0.0;
  detail::filtered_determinant(u, v, w, det, permanent);
  const int s = detail::certified_sign(det, permanent);
  if (s != 2) return s;
  if (detail::has_zero_row(u, v, w)) return 0;
  return sign(orientation_value(a, b, c, d));
}

// Sign of det[b - a, c - a, direction].
SHADOWCTS_HD inline int orientation_towards(const glm::dvec3& a, const glm::dvec3& b,
                                            const glm::dvec3& c, const glm::dvec3& direction) {
  double u[3], v[3], w[3];
  for (int i = 0; i < 3; ++i) {
    u[i] = rounded_sub(b[i], a[i]);
    v[i] = rounded_sub(c[i], a[i]);
    w[i] = direction[i];
  }
  double det = 0.0, permanent = 0.0;
  detail::filtered_determinant(u, v, w, det, permanent);
  const int s = detail::certified_sign(det, permanent);
  if (s != 2) return s;
  if (detail::has_zero_row(u, v, w)) return 0;
  return sign(orientation_towards_value(a, b, c, direction));
}

SHADOWCTS_GEOMETRY_ABI_END
}  // namespace shadowcts::geometry
