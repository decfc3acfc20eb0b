#pragma once
// The oracles' test of whether a moved coordinate is a double: where it is, CGAL's filtered
// predicates take it as is; where not, the oracle builds it in exact rationals.
#include <cmath>

namespace shadowcts {

// a + b when the double sum is exact: Knuth's two-sum recovers the rounding error exactly, and the
// sum is exact iff that error is zero. False on overflow.
inline bool exact_double_sum(double a, double b, double& sum) {
  sum = a + b;
  if (!std::isfinite(sum)) return false;
  const double b_virtual = sum - a;
  const double a_virtual = sum - b_virtual;
  return (a - a_virtual) + (b - b_virtual) == 0.0;
}

}  // namespace shadowcts
