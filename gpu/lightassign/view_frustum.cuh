#pragma once
// The camera as the light-assignment kernels see it: ViewFrustum (reference/lightassign/
// view_frustum.h) on the device, every double operation one IEEE rounding in the reference's
// order (rounded_arithmetic.h keeps nvcc from fusing them), so depths, sub-frustum boxes, plane
// tests and screen rectangles are the reference's bit for bit.
#include <cmath>
#include <cstdint>

#include "gpu/emulator/kernel.h"
#include "gpu/lightassign/lightassign_kernels.h"
#include "shadowcts/geometry/rounded_arithmetic.h"

namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE::lightassign {

// A screen rectangle in pixel-boundary coordinates and a depth range (SubFrustum).
struct SubFrustum {
  double x0 = 0, x1 = 0, y0 = 0, y1 = 0;
  double near_depth = 0, far_depth = 0;
};

// The tiles a light's screen rectangle covers (TileRect); empty when x0 > x1.
struct TileRect {
  std::uint32_t x0 = 1, x1 = 0, y0 = 1, y1 = 0;
};

__device__ inline double dmin(double a, double b) {
  return b < a ? b : a;  // std::min's choice
}

__device__ inline double dmax(double a, double b) {
  return a < b ? b : a;  // std::max's choice
}

// glm::dot's order: (x + y) + z.
__device__ inline double dot3(const glm::dvec3& a, const glm::dvec3& b) {
  return rounded_add(rounded_add(rounded_mul(a.x, b.x), rounded_mul(a.y, b.y)),
                     rounded_mul(a.z, b.z));
}

__device__ inline glm::dvec3 minus(const glm::dvec3& a, const glm::dvec3& b) {
  return {rounded_sub(a.x, b.x), rounded_sub(a.y, b.y), rounded_sub(a.z, b.z)};
}

__device__ inline double length3(const glm::dvec3& a) {
  return sqrt(dot3(a, a));
}

__device__ inline double view_depth(const LightAssignFrame& f, const glm::vec3& p) {
  return dot3(minus(glm::dvec3(p), f.origin), f.forward);
}

__device__ inline glm::dvec3 to_view(const LightAssignFrame& f, const glm::dvec3& p) {
  const glm::dvec3 v = minus(p, f.origin);
  return {dot3(v, f.right), dot3(v, f.up), dot3(v, f.forward)};
}

__device__ inline double slope_x(const LightAssignFrame& f, double x) {
  return rounded_mul(
      rounded_mul(rounded_sub(rounded_mul(2.0, x) / double(f.width), 1.0), f.tan_half_fov),
      f.aspect);
}

__device__ inline double slope_y(const LightAssignFrame& f, double y) {
  return rounded_mul(rounded_sub(1.0, rounded_mul(2.0, y) / double(f.height)), f.tan_half_fov);
}

__device__ inline double pixel_x(const LightAssignFrame& f, double slope) {
  return rounded_mul(
      rounded_mul(rounded_add(slope / rounded_mul(f.tan_half_fov, f.aspect), 1.0), 0.5),
      double(f.width));
}

__device__ inline double pixel_y(const LightAssignFrame& f, double slope) {
  return rounded_mul(rounded_mul(rounded_sub(1.0, slope / f.tan_half_fov), 0.5), double(f.height));
}

__device__ inline float round_down(double x) {
  float r = float(x);
  if (double(r) > x) r = nextafterf(r, -INFINITY);
  return r;
}

__device__ inline float round_up(double x) {
  float r = float(x);
  if (double(r) < x) r = nextafterf(r, INFINITY);
  return r;
}

// ViewFrustum::bounding_box: the float box around the sub-frustum's corners, grown by 2^-40 of
// the magnitudes and rounded outwards.
__device__ inline LightAssignBox bounding_box(const LightAssignFrame& frame, const SubFrustum& f) {
  double low[3] = {INFINITY, INFINITY, INFINITY}, high[3] = {-INFINITY, -INFINITY, -INFINITY};
  double magnitude = length3(frame.origin);
  const double depths[2] = {f.near_depth, f.far_depth};
  const double ys[2] = {f.y0, f.y1}, xs[2] = {f.x0, f.x1};
  for (const double d : depths)
    for (const double y : ys)
      for (const double x : xs) {
        const double sx = slope_x(frame, x), sy = slope_y(frame, y);
        glm::dvec3 c;
        for (int i = 0; i < 3; ++i) {
          const double ray =
              rounded_add(rounded_add(frame.forward[i], rounded_mul(sx, frame.right[i])),
                          rounded_mul(sy, frame.up[i]));
          c[i] = rounded_add(frame.origin[i], rounded_mul(d, ray));
          low[i] = dmin(low[i], c[i]);
          high[i] = dmax(high[i], c[i]);
        }
        magnitude = dmax(magnitude, rounded_add(length3(c), length3(minus(c, frame.origin))));
      }
  const double margin = rounded_mul(0x1p-40, magnitude);
  LightAssignBox box;
  for (int i = 0; i < 3; ++i) {
    box.min[i] = round_down(rounded_sub(low[i], margin));
    box.max[i] = round_up(rounded_add(high[i], margin));
  }
  return box;
}

// grow_to_contain: whether p grew the box.
__device__ inline bool grow_to_contain(LightAssignBox& box, const glm::vec3& p) {
  bool grew = false;
  for (int i = 0; i < 3; ++i) {
    if (p[i] < box.min[i]) box.min[i] = p[i], grew = true;
    if (p[i] > box.max[i]) box.max[i] = p[i], grew = true;
  }
  return grew;
}

// ViewFrustum::sphere_may_meet: false only when the sphere lies beyond one of the sub-frustum's
// six planes by more than a rounding margin.
__device__ inline bool sphere_may_meet(const LightAssignFrame& frame, const SubFrustum& f,
                                       const glm::dvec3& centre, double radius) {
  const glm::dvec3 v = to_view(frame, centre);
  const double margin = rounded_mul(
      0x1p-40, rounded_add(rounded_add(rounded_add(length3(centre), length3(frame.origin)), radius),
                           f.far_depth));
  const double reach = rounded_add(radius, margin);
  if (v.z < rounded_sub(f.near_depth, reach) || v.z > rounded_add(f.far_depth, reach)) return false;
  const double sx0 = slope_x(frame, f.x0), sx1 = slope_x(frame, f.x1);
  const double sy0 = slope_y(frame, f.y0), sy1 = slope_y(frame, f.y1);
  auto outside = [&](double along, double slope) {
    return rounded_sub(along, rounded_mul(slope, v.z)) /
               sqrt(rounded_add(1.0, rounded_mul(slope, slope))) <
           -reach;
  };
  if (outside(v.x, sx0)) return false;
  if (outside(-v.x, -sx1)) return false;
  if (outside(-v.y, -sy0)) return false;
  if (outside(v.y, sy1)) return false;
  return true;
}

// covered_tiles (reference/lightassign/tiled_assignment.cpp): the tiles the screen-space
// bounding rectangle of the light's sphere covers.
__device__ inline TileRect covered_tiles(const LightAssignFrame& frame,
                                         const LightAssignSphere& light, std::uint32_t tile_size,
                                         std::uint32_t tiles_x, std::uint32_t tiles_y) {
  const glm::dvec3 v = to_view(frame, glm::dvec3(light.centre));
  const double r = light.range;
  TileRect rect;
  if (rounded_add(v.z, r) <= 0.0) return rect;
  const double width = frame.width, height = frame.height;
  double px0 = -1.0, px1 = rounded_add(width, 1.0), py0 = -1.0, py1 = rounded_add(height, 1.0);
  if (rounded_sub(v.z, r) > rounded_mul(0x1p-30, rounded_add(fabs(v.z), r))) {
    const double denominator = rounded_sub(rounded_mul(v.z, v.z), rounded_mul(r, r));
    auto slopes = [&](double along, double& low, double& high) {
      const double root =
          rounded_mul(r, sqrt(dmax(0.0, rounded_add(rounded_mul(along, along), denominator))));
      low = rounded_sub(rounded_mul(along, v.z), root) / denominator;
      high = rounded_add(rounded_mul(along, v.z), root) / denominator;
    };
    double sx0, sx1, sy0, sy1;
    slopes(v.x, sx0, sx1);
    slopes(v.y, sy0, sy1);
    const double margin_x = rounded_add(1e-3, rounded_mul(0x1p-30, width));
    const double margin_y = rounded_add(1e-3, rounded_mul(0x1p-30, height));
    px0 = rounded_sub(pixel_x(frame, sx0), margin_x);
    px1 = rounded_add(pixel_x(frame, sx1), margin_x);
    py0 = rounded_sub(pixel_y(frame, sy1), margin_y);
    py1 = rounded_add(pixel_y(frame, sy0), margin_y);
  }
  if (px1 < 0.0 || py1 < 0.0 || px0 > width || py0 > height) return rect;
  auto tile = [&](double pixel, std::uint32_t tiles) {
    const double t = floor(pixel / double(tile_size)), top = double(tiles - 1);
    return std::uint32_t(t < 0.0 ? 0.0 : top < t ? top : t);  // std::clamp
  };
  rect.x0 = tile(px0, tiles_x);
  rect.x1 = tile(px1, tiles_x);
  rect.y0 = tile(py0, tiles_y);
  rect.y1 = tile(py1, tiles_y);
  return rect;
}

}  // namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE::lightassign
