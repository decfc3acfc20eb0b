#pragma once
// Whether a triangle lies beside everything a fragment's sun disk can see, from the triangle's
// light-space box alone: softtile's early-out before the per-fragment setup, written once for
// the reference, the simd port (per fragment, and per block of fragments) and the CUDA kernels,
// so that all of them skip the same (fragment, triangle) pairs.
//
// A point q is seen inside the disk of the fragment p only if |q.xy - p.xy| <= (q.z - p.z) r, r
// the disk's tangent radius (1 / inverse_scale: tan(a), or the post's sin(a)). With q in the
// triangle's box [x0, x1] x [y0, y1] and q.z <= z1 that needs p.x - x1 <= (z1 - p.z) r, and the
// like on the other three sides. beside_disk() says true only where one side fails by a margin
// that covers the rounding of this test and of the setup's h = ((q - p).xy inverse_scale,
// rotated; (q - p).z): 2^-8 of the reach (reach_per_height), and 2^-18 of the coordinates'
// magnitude (the rotation's products err by ~2^-23 of |h.xy|). Every vertex's h then lies in the
// open half-space beyond that side of the cone |h.xy| <= h.z, and so does the whole triangle:
// it covers no cell of the disk (every cell centre lies inside the unit disk), so skipping its
// setup changes no mask. All operations are single roundings (rounded_arithmetic.h), so host and
// device decide alike.
#include <cmath>  // std::nextafter
#include <limits>

#include "shadowcts/geometry/rounded_arithmetic.h"
#include "shadowcts/host_device.h"

namespace shadowcts {
SHADOWCTS_GEOMETRY_ABI_BEGIN

// |x| in float on host and device alike (no overload of fabs to resolve to double).
SHADOWCTS_HD inline float float_magnitude(float x) {
  return x < 0.0f ? -x : x;
}

struct LightSpaceBox {
  float x0, x1, y0, y1;  // the triangle's light-space x and y ranges
  float z1;              // its highest vertex
  float magnitude;       // the largest |x| or |y| of its vertices
};

// v: the three light-space vertices, x y z each.
SHADOWCTS_HD inline LightSpaceBox light_space_box(const float* v) {
  LightSpaceBox box{v[0], v[0], v[1], v[1], v[2], 0.0f};
  for (int i = 0; i < 3; ++i) {
    const float x = v[3 * i], y = v[3 * i + 1], z = v[3 * i + 2];
    box.x0 = x < box.x0 ? x : box.x0;
    box.x1 = x > box.x1 ? x : box.x1;
    box.y0 = y < box.y0 ? y : box.y0;
    box.y1 = y > box.y1 ? y : box.y1;
    box.z1 = z > box.z1 ? z : box.z1;
    const float m =
        float_magnitude(x) > float_magnitude(y) ? float_magnitude(x) : float_magnitude(y);
    box.magnitude = m > box.magnitude ? m : box.magnitude;
  }
  return box;
}

// The disk's reach per unit of height, 1 / inverse_scale with the margin 2^-8, rounded up. Host
// only: the kernels get it as a parameter.
inline float disk_reach_per_height(float inverse_scale) {
  const double reach = 1.0 / double(inverse_scale) * (1.0 + 0x1p-8);
  float k = float(reach);
  if (double(k) < reach) k = std::nextafter(k, std::numeric_limits<float>::infinity());
  return k;
}

// How far beside the box a fragment `height` below its top may lie and still see it; coordinates
// bounds |p.x| + |p.y| + the box's magnitude. Monotone in both, so a bound for a block of
// fragments (its lowest z, its largest |x| + |y|) gives at least every fragment's reach.
SHADOWCTS_HD inline float disk_reach(float height, float coordinates, float reach_per_height) {
  const float slack = rounded_add(rounded_mul(coordinates, 0x1p-18f), 0x1p-120f);
  return rounded_add(rounded_mul(height, reach_per_height), slack);
}

// True: the triangle (its box) lies beside the disk of the fragment at (px, py, pz). False where
// no vertex lies above the fragment (the setup rejects it there) and for NaN.
SHADOWCTS_HD inline bool beside_disk(float px, float py, float pz, const LightSpaceBox& box,
                                     float reach_per_height) {
  const float height = rounded_sub(box.z1, pz);
  if (!(height > 0.0f)) return false;
  const float coordinates =
      rounded_add(rounded_add(float_magnitude(px), float_magnitude(py)), box.magnitude);
  const float reach = disk_reach(height, coordinates, reach_per_height);
  return rounded_sub(px, box.x1) > reach || rounded_sub(box.x0, px) > reach ||
         rounded_sub(py, box.y1) > reach || rounded_sub(box.y0, py) > reach;
}

SHADOWCTS_GEOMETRY_ABI_END
}  // namespace shadowcts
