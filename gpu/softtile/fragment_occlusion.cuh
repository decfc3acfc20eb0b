#pragma once
// The per-fragment triangle setup on the device: reference/softtile/fragment_occlusion.cpp's
// triangle_edges, in float, every operation the reference's (glm's cross and dot, the sign applied
// by a multiplication) in its order and rounded once (no FMA under nvcc), so the edge functions
// and the accept / reject decisions are the reference's bit for bit.
#include <cmath>

#include "gpu/emulator/kernel.h"
#include "gpu/softtile/softtile_kernel.h"
#include "shadowcts/geometry/disk_reach.h"
#include "shadowcts/geometry/rounded_arithmetic.h"

namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE {
namespace softtile {

__device__ inline bool is_finite(float x) {
#if SHADOWCTS_EMULATED
  return std::isfinite(x);
#else
  return isfinite(x);
#endif
}

// glm::cross(a, b) = (a.y b.z - b.y a.z, a.z b.x - b.z a.x, a.x b.y - b.x a.y).
__device__ inline void cross3(const float a[3], const float b[3], float out[3]) {
  out[0] = rounded_sub(rounded_mul(a[1], b[2]), rounded_mul(b[1], a[2]));
  out[1] = rounded_sub(rounded_mul(a[2], b[0]), rounded_mul(b[2], a[0]));
  out[2] = rounded_sub(rounded_mul(a[0], b[1]), rounded_mul(b[0], a[1]));
}

// The reference's FragmentSetup (its inverse scale is the same for every fragment).
struct FragmentSetup {
  float position[3];  // light space
  float cos_rotation, sin_rotation;
};

// The three edge functions of the triangle seen from the fragment, edges[3 i + c] component c of
// edge i; false when it cannot touch the disk (the reference's triangle_edges, its early-out by
// the light-space box first).
__device__ inline bool triangle_edges(const FragmentSetup& fragment, float inverse_scale,
                                      float reach_per_height, const SofttileTriangle& triangle,
                                      float edges[9]) {
  if (beside_disk(fragment.position[0], fragment.position[1], fragment.position[2],
                  light_space_box(triangle.vertices), reach_per_height))
    return false;
  float h[3][3];
  bool any_front = false;
  for (int i = 0; i < 3; ++i) {
    const float tx = rounded_sub(triangle.vertices[3 * i], fragment.position[0]);
    const float ty = rounded_sub(triangle.vertices[3 * i + 1], fragment.position[1]);
    const float tz = rounded_sub(triangle.vertices[3 * i + 2], fragment.position[2]);
    const float x = rounded_mul(tx, inverse_scale), y = rounded_mul(ty, inverse_scale);
    // Rotating the triangle by the angle rotates the grid by its opposite: the disk is round.
    h[i][0] =
        rounded_sub(rounded_mul(fragment.cos_rotation, x), rounded_mul(fragment.sin_rotation, y));
    h[i][1] =
        rounded_add(rounded_mul(fragment.sin_rotation, x), rounded_mul(fragment.cos_rotation, y));
    h[i][2] = tz;
    any_front = any_front || tz > 0.0f;
  }
  if (!any_front) return false;
  float c[3];
  cross3(h[1], h[2], c);
  const float det = rounded_add(rounded_add(rounded_mul(h[0][0], c[0]), rounded_mul(h[0][1], c[1])),
                                rounded_mul(h[0][2], c[2]));
  if (det == 0.0f || !is_finite(det)) return false;
  const float sign = det > 0.0f ? 1.0f : -1.0f;
  for (int i = 0; i < 3; ++i) {
    float e[3];
    cross3(h[i], h[(i + 1) % 3], e);
    for (int k = 0; k < 3; ++k) edges[3 * i + k] = rounded_mul(sign, e[k]);
    const float ex = edges[3 * i], ey = edges[3 * i + 1], ez = edges[3 * i + 2];
    // The disk lies entirely outside this edge: a X + b Y + c < -|(a, b)| on the whole unit disk.
    if (ez < 0.0f && rounded_mul(ez, ez) > rounded_add(rounded_mul(ex, ex), rounded_mul(ey, ey)))
      return false;
  }
  return true;
}

}  // namespace softtile
}  // namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE
