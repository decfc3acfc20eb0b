#pragma once
// Sun-disk cases for the soft-shadow tests: the hand-built hard-shadow scaffolding (a non-caster
// ground in y = 0 spanning [-8, 8]^2) under a sun disk, and subsampled fixture views.
#include <cmath>
#include <numbers>

#include "shadowcts/case.h"
#include "shadowcts/view_samples.h"
#include "tests/oracles/hand_built_case.h"

namespace shadowcts::testing {

inline ShadowLight sun_disk(const glm::vec3& direction, double angular_radius_degrees) {
  ShadowLight light;
  light.kind = ShadowLightKind::sun_disk;
  light.direction = direction;
  light.angular_radius = float(angular_radius_degrees * std::numbers::pi / 180.0);
  return light;
}

// Keeps every `stride`-th regular sample regular and marks the others sky (not compared), so the
// exact oracle's cost in CI stays small while the samples still cover the whole image.
inline ViewSamples every_nth_regular(const ViewSamples& samples, std::size_t stride,
                                     std::size_t offset = 0) {
  ViewSamples kept = samples;
  std::size_t regular = 0;
  for (ViewSample& s : kept.samples) {
    if (s.sample_class != SampleClass::regular) continue;
    if ((regular++ + offset) % stride != 0) s.sample_class = SampleClass::sky;
  }
  return kept;
}

}  // namespace shadowcts::testing
