#pragma once
// The tile's cone culling on the device: reference/softtile/shadow_cone.cpp's may_shadow, in
// double, every operation the reference's in the reference's order and rounded once
// (shadowcts/geometry/rounded_arithmetic.h: nvcc may not fuse them into FMAs), so a tile's
// candidate list is the reference's. The bound's own terms (middle, enclosing radius, |a|, ...) and
// cos / sin of the disk's radius come from the host (softtile_kernel.h).
#include <cmath>

#include "gpu/emulator/kernel.h"
#include "gpu/softtile/softtile_kernel.h"
#include "shadowcts/geometry/rounded_arithmetic.h"

namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE {
namespace softtile {

// The reference's relative margin.
constexpr double relative_margin = 1e-9;

__device__ inline double square_root(double x) {
#if SHADOWCTS_EMULATED
  return std::sqrt(x);
#else
  return sqrt(x);  // IEEE round-to-nearest, as the host's
#endif
}

__device__ inline double absolute(double x) {
#if SHADOWCTS_EMULATED
  return std::fabs(x);
#else
  return fabs(x);
#endif
}

// glm's dot of double vectors: (x x' + y y') + z z'.
__device__ inline double dot3(const double a[3], const double b[3]) {
  return rounded_add(rounded_add(rounded_mul(a[0], b[0]), rounded_mul(a[1], b[1])),
                     rounded_mul(a[2], b[2]));
}

// glm::length: sqrt(dot(v, v)).
__device__ inline double length3(const double v[3]) {
  return square_root(dot3(v, v));
}

// std::max(x, y) and std::min(x, y): their NaN and tie behaviour included.
__device__ inline double std_max(double x, double y) {
  return x < y ? y : x;
}
__device__ inline double std_min(double x, double y) {
  return y < x ? y : x;
}

// gap(cone, x, radius) = distance_to_cone(cone, x) - radius - slack, the cone (tip, -d, a).
__device__ inline double gap(const SofttileSun& sun, const SofttileCone& cone, const double x[3],
                             double radius) {
  double v[3];
  for (int k = 0; k < 3; ++k) v[k] = rounded_sub(x[k], cone.tip[k]);
  const double length_v = length3(v);
  const double slack = rounded_mul(relative_margin, rounded_add(length_v, radius));
  const double h = dot3(v, sun.axis);
  double lateral_v[3];
  for (int k = 0; k < 3; ++k) lateral_v[k] = rounded_sub(v[k], rounded_mul(h, sun.axis[k]));
  const double l = length3(lateral_v);
  // In the (height, lateral) half-plane the cone is the wedge below the ray (cos a, sin a).
  const double distance =
      rounded_add(rounded_mul(h, sun.cos_radius), rounded_mul(l, sun.sin_radius)) <= 0.0
          ? length_v
          : std_max(0.0,
                    rounded_sub(rounded_mul(l, sun.cos_radius), rounded_mul(h, sun.sin_radius)));
  return rounded_sub(rounded_sub(distance, radius), slack);
}

// height(x) = dot(tip - x, d).
__device__ inline double height(const SofttileSun& sun, const SofttileCone& cone,
                                const double x[3]) {
  double v[3];
  for (int k = 0; k < 3; ++k) v[k] = rounded_sub(cone.tip[k], x[k]);
  return dot3(v, sun.direction);
}

// g(s) of the capsule: the gap at a + s (b - a) with radius ra + s (rb - ra).
__device__ inline double capsule_gap(const SofttileSun& sun, const SofttileCone& cone,
                                     const SofttileBound& bound, double s) {
  double x[3];
  for (int k = 0; k < 3; ++k) x[k] = rounded_add(bound.a[k], rounded_mul(s, bound.ab[k]));
  return gap(sun, cone, x, rounded_add(bound.radius_a, rounded_mul(s, bound.dr)));
}

// The reference's may_shadow(sun, cone, bound).
__device__ inline bool may_shadow(const SofttileSun& sun, const SofttileCone& cone,
                                  const SofttileBound& bound) {
  // relative_margin * (|tip| + |a| + |b| + ra + rb), left to right.
  const double height_slack = rounded_mul(
      relative_margin,
      rounded_add(
          rounded_add(rounded_add(rounded_add(cone.tip_length, bound.length_a), bound.length_b),
                      bound.radius_a),
          bound.radius_b));
  const double floor = rounded_sub(cone.start_height, height_slack);
  if (!bound.capsule) {
    if (rounded_add(height(sun, cone, bound.a), bound.radius_a) < floor) return false;
    return gap(sun, cone, bound.a, bound.radius_a) <= 0.0;
  }
  // Truncation: the capsule's highest reach below the tip is at one of its end spheres.
  if (std_max(rounded_add(height(sun, cone, bound.a), bound.radius_a),
              rounded_add(height(sun, cone, bound.b), bound.radius_b)) < floor)
    return false;
  // Cheap reject first: the sphere around the whole capsule.
  if (gap(sun, cone, bound.middle, bound.enclosing) > 0.0) return false;
  // g is convex: ternary search for its minimum, then allow for the remaining interval with g's
  // Lipschitz constant.
  const double g0 = capsule_gap(sun, cone, bound, 0.0), g1 = capsule_gap(sun, cone, bound, 1.0);
  if (g0 <= 0.0 || g1 <= 0.0) return true;
  double lo = 0.0, hi = 1.0;
  for (int i = 0; i < 40; ++i) {
    const double third = rounded_sub(hi, lo) / 3.0;
    const double m1 = rounded_add(lo, third), m2 = rounded_sub(hi, third);
    const double gm1 = capsule_gap(sun, cone, bound, m1), gm2 = capsule_gap(sun, cone, bound, m2);
    if (gm1 <= 0.0 || gm2 <= 0.0) return true;
    if (gm1 <= gm2)
      hi = m2;
    else
      lo = m1;
  }
  // std::min({g(lo), g(hi), g(mid), g(0), g(1)}): the first smallest under <.
  double best = capsule_gap(sun, cone, bound, lo);
  best = std_min(best, capsule_gap(sun, cone, bound, hi));
  best = std_min(best, capsule_gap(sun, cone, bound, rounded_mul(0.5, rounded_add(lo, hi))));
  best = std_min(best, g0);
  best = std_min(best, g1);
  return rounded_sub(best, rounded_mul(bound.lipschitz, rounded_sub(hi, lo))) <= 0.0;
}

}  // namespace softtile
}  // namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE
