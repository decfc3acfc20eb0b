#pragma once
// The cull every listed light passes, as in the reference: the closed ball |x - c| <= r meets the
// closed float box, decided exactly. The lanes evaluate the reference's double filter and hand the
// pairs it cannot decide to sphere_meets_box_exact, which decides them with floating-point
// expansions (include/shadowcts/geometry/expansion.h) instead of the reference's rationals: an
// exact answer is the same answer, so the lists are the same.
#include "shadowcts/algorithm.h"

namespace shadowcts::simd {

// The double filter's bound, as the reference's: |computed - exact| of the squared distance is
// below 16 u sum_i (|low_i| + |c_i| + |high_i|)^2, plus a guard against underflow.
inline constexpr double sphere_box_error_scale = 16.0 * 0x1p-53;
inline constexpr double sphere_box_underflow_guard = 0x1p-1000;

bool sphere_meets_box_exact(const glm::vec3& centre, float range, const Aabb& box);

}  // namespace shadowcts::simd
