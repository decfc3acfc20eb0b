#pragma once
// Exact test for triangles of zero area (collinear or coincident float vertices), which cast no
// shadow. Twice the vector area is a×b + b×c + c×a; each component is a sum of six products of
// two floats. A product of two floats is exact in double (24 + 24 significand bits, exponents far
// inside double's range), so a component is zero exactly when the exact sum of six doubles is
// zero. Expansion arithmetic (Knuth's two-sum, Shewchuk's grow-expansion) decides that without
// rounding error; it costs ~100 double additions and runs only when a ray test reports a hit.
#include <glm/vec3.hpp>

#include "shadowcts/geometry/rounded_arithmetic.h"
#include "shadowcts/host_device.h"

namespace shadowcts {
SHADOWCTS_GEOMETRY_ABI_BEGIN

struct TwoSum {
  double sum;    // a + b rounded
  double error;  // exactly (a + b) - sum
};

// Knuth's branch-free two-sum: exact for any doubles as long as nothing overflows.
SHADOWCTS_HD inline TwoSum two_sum(double a, double b) {
  const double sum = rounded_add(a, b);
  const double b_virtual = rounded_sub(sum, a);
  const double a_virtual = rounded_sub(sum, b_virtual);
  const double b_roundoff = rounded_sub(b, b_virtual);
  const double a_roundoff = rounded_sub(a, a_virtual);
  return {sum, rounded_add(a_roundoff, b_roundoff)};
}

// Whether the exact (unrounded) sum of the terms is zero. Grows a nonoverlapping expansion term by
// term and drops zero components; a nonoverlapping expansion is zero iff it has no components.
template <int term_count>
SHADOWCTS_HD inline bool exact_sum_is_zero(const double (&terms)[term_count]) {
  double expansion[term_count];
  int length = 0;
  for (int i = 0; i < term_count; ++i) {
    double carry = terms[i];
    int kept = 0;
    for (int j = 0; j < length; ++j) {
      const TwoSum step = two_sum(carry, expansion[j]);
      if (step.error != 0.0) expansion[kept++] = step.error;  // kept <= j: slot already read
      carry = step.sum;
    }
    if (carry != 0.0) expansion[kept++] = carry;
    length = kept;
  }
  return length == 0;
}

// Exact product of two floats.
SHADOWCTS_HD inline double exact_product(float a, float b) {
  return rounded_mul(static_cast<double>(a), static_cast<double>(b));
}

// One component of a×b + b×c + c×a, from the two other coordinate axes (i, j) of the vertices.
SHADOWCTS_HD inline bool vector_area_component_is_zero(float ai, float aj, float bi, float bj,
                                                       float ci, float cj) {
  const double terms[6] = {exact_product(ai, bj),  -exact_product(aj, bi), exact_product(bi, cj),
                           -exact_product(bj, ci), exact_product(ci, aj),  -exact_product(cj, ai)};
  return exact_sum_is_zero(terms);
}

// True when the three vertices lie on one line (the triangle's area is exactly zero).
SHADOWCTS_HD inline bool triangle_has_zero_area(const glm::vec3& a, const glm::vec3& b,
                                                const glm::vec3& c) {
  return vector_area_component_is_zero(a.y, a.z, b.y, b.z, c.y, c.z) &&
         vector_area_component_is_zero(a.z, a.x, b.z, b.x, c.z, c.x) &&
         vector_area_component_is_zero(a.x, a.y, b.x, b.y, c.x, c.y);
}

SHADOWCTS_GEOMETRY_ABI_END
}  // namespace shadowcts
