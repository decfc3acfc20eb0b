#pragma once
// Whether a sample lies in a ranged light's volume, decided the way a light loop would but
// without ever dropping a light that lights the sample: the sphere exactly (the shared
// sphere-box predicate with a one-point box), a spot's cone by a double evaluation with a proven
// error bound. Where the bound cannot decide (the sample within rounding of the cone's surface:
// cos of the half angle is transcendental, so no finite evaluation ties it) the light is kept,
// and counted. Independent of the light-assignment oracle, which decides the cone with MPFR.
#include <cstdint>

#include <glm/vec3.hpp>

#include "shadowcts/case.h"

namespace shadowcts {

struct LightVolumeCheck {
  RangedLight light;
  double cos_half_angle = 0.0;  // spot: cos of the float half angle, rounded
  double axis_length = 0.0;     // spot: |direction|, rounded

  explicit LightVolumeCheck(const RangedLight& l);

  // 1 inside, 0 outside, -1 undecided within rounding of a spot cone's surface (keep the light).
  int contains(const glm::vec3& x) const;
};

}  // namespace shadowcts
