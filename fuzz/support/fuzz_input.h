#pragma once
// Reading geometry from fuzz bytes. Dyadic values (integers times a power of two) with few
// significant bits are exact in float, and so are their sums, differences and small multiples:
// a point "on an edge" built from them is exactly on it.
#include <cmath>
#include <cstdint>

#include <fuzzer/FuzzedDataProvider.h>
#include <glm/vec3.hpp>

namespace shadowcts::fuzzing {

// k / 2^fraction_bits for an integer k in [-limit, limit].
inline float dyadic(FuzzedDataProvider& in, int limit, int fraction_bits) {
  return std::ldexp(float(in.ConsumeIntegralInRange<int>(-limit, limit)), -fraction_bits);
}

inline glm::vec3 dyadic_point(FuzzedDataProvider& in, int limit, int fraction_bits) {
  const float x = dyadic(in, limit, fraction_bits);
  const float y = dyadic(in, limit, fraction_bits);
  return {x, y, dyadic(in, limit, fraction_bits)};
}

// An exact rigid symmetry of the axes (a permutation and sign flips), as a function.
struct AxisSymmetry {
  int axis[3] = {0, 1, 2};
  float sign[3] = {1.0f, 1.0f, 1.0f};

  static AxisSymmetry read(FuzzedDataProvider& in) {
    static constexpr int permutations[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2},
                                               {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    AxisSymmetry s;
    const int p = in.ConsumeIntegralInRange<int>(0, 5);
    for (int k = 0; k < 3; ++k) {
      s.axis[k] = permutations[p][k];
      s.sign[k] = in.ConsumeBool() ? -1.0f : 1.0f;
    }
    return s;
  }
  glm::vec3 operator()(const glm::vec3& v) const {
    return {sign[0] * v[axis[0]], sign[1] * v[axis[1]], sign[2] * v[axis[2]]};
  }
};

// Moves `v` by up to `max_ulps` float steps in each coordinate, as the bytes say ("within a few
// ulps" of an exact feature).
inline glm::vec3 ulp_jitter(FuzzedDataProvider& in, glm::vec3 v, int max_ulps) {
  for (int k = 0; k < 3; ++k) {
    const int steps = in.ConsumeIntegralInRange<int>(-max_ulps, max_ulps);
    for (int s = 0; s < std::abs(steps); ++s)
      v[k] = std::nextafter(v[k], steps > 0 ? INFINITY : -INFINITY);
  }
  return v;
}

}  // namespace shadowcts::fuzzing
