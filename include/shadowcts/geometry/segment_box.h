#pragma once
// The bounding box of a shadow segment (sample to point light) or ray (sample towards a
// directional light, unbounded on the light's side), against a triangle's box: a triangle whose
// box misses it cannot meet the segment. Float bounds compared in float are exact, so the test
// only drops triangles that the exact segment misses, and it costs a few comparisons where a
// segment/triangle test costs a transform of three vertices.
#include <cmath>

#include <glm/vec3.hpp>

#include "shadowcts/host_device.h"

namespace shadowcts {
SHADOWCTS_GEOMETRY_ABI_BEGIN

// Plain floats, so that it can sit in CUDA shared memory.
struct FloatBox {
  float lo[3], hi[3];
};

// light: the point light's position, or the direction towards a directional light.
SHADOWCTS_HD inline FloatBox segment_box(const glm::vec3& sample, const glm::vec3& light,
                                         bool directional) {
  FloatBox box{};
  for (int k = 0; k < 3; ++k) {
    const float p = sample[k], l = light[k];
    box.lo[k] = directional ? (l < 0.0f ? -INFINITY : p) : (p < l ? p : l);
    box.hi[k] = directional ? (l > 0.0f ? INFINITY : p) : (p > l ? p : l);
  }
  return box;
}

SHADOWCTS_HD inline float min_of_three(float a, float b, float c) {
  const float ab = a < b ? a : b;
  return ab < c ? ab : c;
}

SHADOWCTS_HD inline float max_of_three(float a, float b, float c) {
  const float ab = a > b ? a : b;
  return ab > c ? ab : c;
}

// The bounding box of a triangle.
SHADOWCTS_HD inline FloatBox triangle_box(const glm::vec3& v0, const glm::vec3& v1,
                                          const glm::vec3& v2) {
  FloatBox box{};
  for (int k = 0; k < 3; ++k) {
    box.lo[k] = min_of_three(v0[k], v1[k], v2[k]);
    box.hi[k] = max_of_three(v0[k], v1[k], v2[k]);
  }
  return box;
}

// Closed boxes: touching boxes overlap.
SHADOWCTS_HD inline bool boxes_overlap(const FloatBox& a, const FloatBox& b) {
  return !(a.hi[0] < b.lo[0] || a.lo[0] > b.hi[0] || a.hi[1] < b.lo[1] || a.lo[1] > b.hi[1] ||
           a.hi[2] < b.lo[2] || a.lo[2] > b.hi[2]);
}

SHADOWCTS_GEOMETRY_ABI_END
}  // namespace shadowcts
