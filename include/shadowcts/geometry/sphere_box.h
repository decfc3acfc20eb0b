#pragma once
// The light-assignment cull every listed light passes, for host and device: the closed ball
// |x - c| <= r meets the closed float box. A double filter with a proven error bound decides
// almost every pair (the bound of the exact light predicates in
// oracles/light_assignment/light_volume_predicates.cpp: 16 u sum_i (|low_i| + |c_i| + |high_i|)^2
// plus an underflow guard); the rest is decided exactly with floating-point expansions instead of
// rationals. An exact answer is the same answer, so every backend that culls with this gets the
// reference's lists.
#include <cmath>

#include <glm/vec3.hpp>

#include "shadowcts/geometry/expansion.h"
#include "shadowcts/geometry/rounded_arithmetic.h"
#include "shadowcts/host_device.h"

namespace shadowcts::geometry {
SHADOWCTS_GEOMETRY_ABI_BEGIN

inline constexpr double sphere_box_error_scale = 16.0 * 0x1p-53;
inline constexpr double sphere_box_underflow_guard = 0x1p-1000;

// sum_i gap_i^2 - r^2 as an expansion: every gap is the difference of two floats (exact in two
// components), every square and sum exact, so its sign is the answer.
SHADOWCTS_HD inline bool sphere_meets_box_exact(const glm::vec3& centre, float range,
                                                const glm::vec3& low, const glm::vec3& high) {
  Expansion<8> square[3];
  for (int i = 0; i < 3; ++i) {
    square[i].size = 0;
    const double c = centre[i];
    if (c < low[i]) {
      const Expansion<2> gap = difference(low[i], c);
      square[i] = product(gap, gap);
    } else if (c > high[i]) {
      const Expansion<2> gap = difference(c, high[i]);
      square[i] = product(gap, gap);
    }
  }
  const Expansion<2> minus_r2 = negated(scaled(expansion_of(double(range)), double(range)));
  return sign(sum(sum(sum(minus_r2, square[0]), square[1]), square[2])) <= 0;
}

// The filter: +1 meets, -1 misses, 0 undecided (within the rounding bound).
SHADOWCTS_HD inline int sphere_meets_box_filter(const glm::vec3& centre, float range,
                                                const glm::vec3& low, const glm::vec3& high) {
  double distance_squared = 0.0, magnitude_squared = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double c = centre[i], lo = low[i], hi = high[i];
    // Rounding is monotone, so the max of the rounded gaps is the rounded true gap.
    double gap = 0.0;
    const double below = rounded_sub(lo, c), above = rounded_sub(c, hi);
    if (below > gap) gap = below;
    if (above > gap) gap = above;
    const double b = rounded_add(rounded_add(fabs(lo), fabs(c)), fabs(hi));
    distance_squared = rounded_add(distance_squared, rounded_mul(gap, gap));
    magnitude_squared = rounded_add(magnitude_squared, rounded_mul(b, b));
  }
  const double r2 = rounded_mul(double(range), double(range));
  const double error = rounded_add(rounded_mul(sphere_box_error_scale, magnitude_squared),
                                   sphere_box_underflow_guard);
  if (rounded_add(distance_squared, error) < r2) return 1;
  if (rounded_sub(distance_squared, error) > r2) return -1;
  return 0;
}

SHADOWCTS_HD inline bool sphere_meets_box(const glm::vec3& centre, float range,
                                          const glm::vec3& low, const glm::vec3& high) {
  const int filtered = sphere_meets_box_filter(centre, range, low, high);
  if (filtered != 0) return filtered > 0;
  return sphere_meets_box_exact(centre, range, low, high);
}

SHADOWCTS_GEOMETRY_ABI_END
}  // namespace shadowcts::geometry
