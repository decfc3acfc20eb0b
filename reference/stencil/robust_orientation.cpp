#include "reference/stencil/robust_orientation.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <boost/multiprecision/cpp_int.hpp>
#include <glm/common.hpp>

namespace shadowcts::stencil {
namespace {

using Rational = boost::multiprecision::cpp_rational;

int exact_sign(const glm::dvec3& a1, const glm::dvec3& a0, const glm::dvec3& b1,
               const glm::dvec3& b0, const glm::dvec3& c1, const glm::dvec3& c0) {
  Rational a[3], b[3], c[3];
  for (int k = 0; k < 3; ++k) {
    // Conversion from double is exact; so are the differences and products below.
    a[k] = Rational(a1[k]) - Rational(a0[k]);
    b[k] = Rational(b1[k]) - Rational(b0[k]);
    c[k] = Rational(c1[k]) - Rational(c0[k]);
  }
  const Rational det = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                       a[2] * (b[0] * c[1] - b[1] * c[0]);
  return det > 0 ? 1 : (det < 0 ? -1 : 0);
}

// The double determinant and its permanent (the same sum with absolute values).
struct Evaluation {
  double det, permanent, a_norm;
};

Evaluation evaluate(const glm::dvec3& a1, const glm::dvec3& a0, const glm::dvec3& b1,
                    const glm::dvec3& b0, const glm::dvec3& c1, const glm::dvec3& c0) {
  const glm::dvec3 a = a1 - a0, b = b1 - b0, c = c1 - c0;
  const double bc_x = b.y * c.z - b.z * c.y;
  const double bc_y = b.z * c.x - b.x * c.z;
  const double bc_z = b.x * c.y - b.y * c.x;
  Evaluation e;
  e.det = a.x * bc_x + a.y * bc_y + a.z * bc_z;
  e.permanent = std::fabs(a.x) * (std::fabs(b.y * c.z) + std::fabs(b.z * c.y)) +
                std::fabs(a.y) * (std::fabs(b.z * c.x) + std::fabs(b.x * c.z)) +
                std::fabs(a.z) * (std::fabs(b.x * c.y) + std::fabs(b.y * c.x));
  e.a_norm = std::fabs(a.x) + std::fabs(a.y) + std::fabs(a.z);
  return e;
}

// Shewchuk's o3derrboundA, valid when the differences are themselves rounded.
constexpr double half_epsilon = std::numeric_limits<double>::epsilon() / 2.0;
constexpr double error_bound = (7.0 + 56.0 * half_epsilon) * half_epsilon;

// The simulated tie of edge_side for an edge direction b - a = s (u1 - u0), s > 0:
// eps det[w, e_i, a - b] + eps^2 det[w, e_j, a - b].
int edge_side_tie(const glm::dvec3& l0, const glm::dvec3& l1, const glm::dvec3& u1,
                  const glm::dvec3& u0) {
  const glm::dvec3 w = l1 - l0;
  const glm::dvec3 aw(std::fabs(w.x), std::fabs(w.y), std::fabs(w.z));
  const int largest = aw.x >= aw.y && aw.x >= aw.z ? 0 : (aw.y >= aw.z ? 1 : 2);
  const glm::dvec3 zero(0.0);
  for (int step = 1; step <= 2; ++step) {
    glm::dvec3 axis(0.0);
    axis[(largest + step) % 3] = 1.0;
    const int tie = sign_of_determinant(l1, l0, axis, zero, u0, u1);
    if (tie != 0) return tie;
  }
  return 0;
}

}  // namespace

DeterminantEstimate estimate_determinant(const glm::dvec3& a1, const glm::dvec3& a0,
                                         const glm::dvec3& b1, const glm::dvec3& b0,
                                         const glm::dvec3& c1, const glm::dvec3& c0) {
  const Evaluation e = evaluate(a1, a0, b1, b0, c1, c0);
  DeterminantEstimate out;
  out.value = e.det;
  // Each of the six products b_i c_j may underflow, by at most half the smallest subnormal, and
  // is then multiplied by a component of a; the rest is the relative bound, doubled for margin.
  constexpr double tiny = std::numeric_limits<double>::denorm_min();
  out.error = 2.0 * error_bound * e.permanent + 8.0 * tiny * (1.0 + e.a_norm);
  if (!std::isfinite(e.det) || !std::isfinite(out.error))
    out.error = std::numeric_limits<double>::infinity();
  return out;
}

int sign_of_determinant(const glm::dvec3& a1, const glm::dvec3& a0, const glm::dvec3& b1,
                        const glm::dvec3& b0, const glm::dvec3& c1, const glm::dvec3& c0) {
  const Evaluation e = evaluate(a1, a0, b1, b0, c1, c0);
  if (e.det > error_bound * e.permanent) return 1;
  if (-e.det > error_bound * e.permanent) return -1;
  // Every product term vanished: a rounded difference is zero only when it is exactly zero.
  if (e.permanent == 0.0 && std::isfinite(e.det)) return 0;
  return exact_sign(a1, a0, b1, b0, c1, c0);
}

int edge_side(const glm::dvec3& l0, const glm::dvec3& l1, const glm::dvec3& a,
              const glm::dvec3& b) {
  const int side = sign_of_determinant(l1, l0, a, l0, b, l0);
  return side != 0 ? side : edge_side_tie(l0, l1, b, a);
}

int edge_side_along(const glm::dvec3& l0, const glm::dvec3& l1, const glm::dvec3& a,
                    const glm::dvec3& u1, const glm::dvec3& u0) {
  // det[w, a - l0, b - l0] = det[w, a - l0, b - a] = s det[w, a - l0, u1 - u0].
  const int side = sign_of_determinant(l1, l0, a, l0, u1, u0);
  return side != 0 ? side : edge_side_tie(l0, l1, u1, u0);
}

int extruded_edge_side(const glm::dvec3& l0, const glm::dvec3& l1, const glm::dvec3& origin,
                       const glm::dvec3& minuend, const glm::dvec3& subtrahend, double factor,
                       const glm::dvec3& u1, const glm::dvec3& u0) {
  // det[w, a - l0, b - a] = s det[w, a - l0, u1 - u0] with the exact a; first with the rounded a.
  const glm::dvec3 rounded = origin + factor * (minuend - subtrahend);
  const DeterminantEstimate estimate = estimate_determinant(l1, l0, rounded, l0, u1, u0);
  // Three roundings of at most half_epsilon each move a component by at most
  // 3 half_epsilon (|origin| + |factor| (|minuend| + |subtrahend|)) (to first order; 4 for the
  // rest and the subnormals), and det[w, delta, c] <= |delta|_inf |w|_1 |c|_1 (doubled: w and c
  // are rounded here).
  double magnitude = 0.0;
  for (int k = 0; k < 3; ++k)
    magnitude = std::max(
        magnitude, std::fabs(origin[k]) +
                       std::fabs(factor) * (std::fabs(minuend[k]) + std::fabs(subtrahend[k])));
  const glm::dvec3 w = glm::abs(l1 - l0), c = glm::abs(u1 - u0);
  const double moved =
      2.0 * (4.0 * half_epsilon * magnitude + 8.0 * std::numeric_limits<double>::denorm_min()) *
      (w.x + w.y + w.z) * (c.x + c.y + c.z);
  const double bound = estimate.error + moved;
  if (std::isfinite(bound) && std::fabs(estimate.value) > bound) return estimate.value > 0 ? 1 : -1;
  Rational wr[3], ar[3], cr[3];
  for (int k = 0; k < 3; ++k) {
    wr[k] = Rational(l1[k]) - Rational(l0[k]);
    ar[k] = Rational(origin[k]) +
            Rational(factor) * (Rational(minuend[k]) - Rational(subtrahend[k])) - Rational(l0[k]);
    cr[k] = Rational(u1[k]) - Rational(u0[k]);
  }
  const Rational det = wr[0] * (ar[1] * cr[2] - ar[2] * cr[1]) -
                       wr[1] * (ar[0] * cr[2] - ar[2] * cr[0]) +
                       wr[2] * (ar[0] * cr[1] - ar[1] * cr[0]);
  if (det != 0) return det > 0 ? 1 : -1;
  return edge_side_tie(l0, l1, u1, u0);
}

}  // namespace shadowcts::stencil
