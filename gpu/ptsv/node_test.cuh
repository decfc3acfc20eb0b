#pragma once
// A node against a shadow volume and a sample against it, on the device (the reference's
// node_test.h defines both): every plane value with one rounding per operation in the reference's
// order (no FMA), so each verdict is the reference's; a sample within the rounding of a plane is
// decided by the shared exact orientation (shadowcts/geometry/exact_orientation.h), whose sign is
// the reference's exact sign.
#include <cmath>
#include <cstdint>

#include <glm/vec3.hpp>

#include "gpu/emulator/kernel.h"
#include "gpu/ptsv/cluster_keys.cuh"
#include "gpu/ptsv/hierarchy.cuh"
#include "gpu/ptsv/ptsv_kernels.h"
#include "shadowcts/geometry/exact_orientation.h"
#include "shadowcts/geometry/receiver_half_space.h"
#include "shadowcts/geometry/rounded_arithmetic.h"

namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE::ptsv {

using gpu_ptsv::Volume;

// ptsv::Plane::at.
__device__ inline double plane_at(const gpu_ptsv::Plane& p, double x, double y, double z) {
  return rounded_add(rounded_add(rounded_add(rounded_mul(p.normal[0], rounded_sub(x, p.anchor[0])),
                                             rounded_mul(p.normal[1], rounded_sub(y, p.anchor[1]))),
                                 rounded_mul(p.normal[2], rounded_sub(z, p.anchor[2]))),
                     p.shift);
}

// The eight corners of the frustum cell of node `index` at `level` (ptsv::implicit_node_cell and
// ptsv::cell_corners): corner i is x[i & 1], y[(i >> 1) & 1], depth[(i >> 2) & 1].
struct CellCorners {
  double p[8][3];
};

__device__ inline CellCorners implicit_cell_corners(const Layout& layout, const double* slice_start,
                                                    int level, std::uint32_t index) {
  const int free_bits = 5 * (layout.leaf_level - level);
  const std::uint64_t low = std::uint64_t(index) << free_bits;
  const std::uint64_t high = low | ((std::uint64_t(1) << free_bits) - 1);
  const int key_bits = layout.x_bits + layout.y_bits + layout.depth_bits;
  const std::uint64_t key_mask = (std::uint64_t(1) << key_bits) - 1;
  std::uint32_t lx, ly, ls, hx, hy, hs;
  deinterleave(layout, std::uint32_t(low & key_mask), lx, ly, ls);
  deinterleave(layout, std::uint32_t(high & key_mask), hx, hy, hs);
  const double sx[2] = {screen_x_of_column(layout, double(lx * 8)),
                        screen_x_of_column(layout, double((hx + 1) * 8))};
  const double sy[2] = {screen_y_of_row(layout, double((hy + 1) * 8)),
                        screen_y_of_row(layout, double(ly * 8))};
  const double depth[2] = {slice_start[ls], slice_start[hs + 1]};
  CellCorners c;
  for (int i = 0; i < 8; ++i) {
    for (int k = 0; k < 3; ++k) {
      // ray = forward + sx right + sy up; corner = origin + depth ray (glm's order).
      const double ray =
          rounded_add(rounded_add(layout.forward[k], rounded_mul(sx[i & 1], layout.right[k])),
                      rounded_mul(sy[(i >> 1) & 1], layout.up[k]));
      c.p[i][k] = rounded_add(layout.origin[k], rounded_mul(depth[(i >> 2) & 1], ray));
    }
  }
  return c;
}

struct PlaneRange {
  double low, high;
};

// ptsv::plane_range over a box: the trivial-reject point takes lo where the normal is >= 0.
__device__ inline PlaneRange plane_range(const gpu_ptsv::Plane& plane, const NodeBox& box) {
  double reject[3], accept[3];
  for (int k = 0; k < 3; ++k) {
    const bool positive = plane.normal[k] >= 0.0;
    reject[k] = positive ? box.lo[k] : box.hi[k];
    accept[k] = positive ? box.hi[k] : box.lo[k];
  }
  return {plane_at(plane, reject[0], reject[1], reject[2]),
          plane_at(plane, accept[0], accept[1], accept[2])};
}

// ptsv::plane_range over a cell's corners.
__device__ inline PlaneRange plane_range(const gpu_ptsv::Plane& plane, const CellCorners& cell) {
  PlaneRange r;
  r.low = r.high = plane_at(plane, cell.p[0][0], cell.p[0][1], cell.p[0][2]);
  for (int i = 1; i < 8; ++i) {
    const double value = plane_at(plane, cell.p[i][0], cell.p[i][1], cell.p[i][2]);
    r.low = value < r.low ? value : r.low;
    r.high = r.high < value ? value : r.high;
  }
  return r;
}

enum Verdict : std::uint32_t {
  verdict_reject = 0,
  verdict_accept = 1,
  verdict_refine = 2,
  verdict_cull = 3
};

struct Tolerances {
  double rounding, accept_bias;
};

// ptsv::classify_node: the verdict of the four planes, then the culling planes (extra_count > 0
// only where the variant uses them); a reject by the culling planes is verdict_cull.
template <class Bounds>
__device__ inline Verdict classify_node(const Volume& volume, const Bounds& bounds, double reach,
                                        const Tolerances& tol, int culling_count) {
  bool accept = true;
  double triangle_high = 0.0;
  for (int k = 0; k < 4; ++k) {
    const PlaneRange range = plane_range(volume.plane[k], bounds);
    if (range.low > tol.rounding) return verdict_reject;
    const double inside_by = k < 3 ? tol.rounding : rounded_add(tol.rounding, tol.accept_bias);
    if (!(range.high < -inside_by)) accept = false;
    if (k == 3) triangle_high = range.high;
  }
  if (accept && !(triangle_high < -rounded_add(tol.rounding, reach))) accept = false;
  if (accept) return verdict_accept;
  for (int k = 0; k < culling_count; ++k)
    if (plane_range(volume.plane[4 + k], bounds).low > tol.rounding) return verdict_cull;
  return verdict_refine;
}

// ptsv::outside_plane_exactly.
__device__ inline bool outside_plane_exactly(const Volume& volume, int k, const glm::dvec3& p) {
  const float* v = volume.exact_vertices;
  const glm::dvec3 light(volume.exact_light[0], volume.exact_light[1], volume.exact_light[2]);
  const glm::dvec3 vertex[3] = {glm::dvec3(v[0], v[1], v[2]), glm::dvec3(v[3], v[4], v[5]),
                                glm::dvec3(v[6], v[7], v[8])};
  if (k == 3)
    return volume.triangle_outside * geometry::orientation(vertex[0], vertex[1], vertex[2], p) > 0;
  const int first[3] = {0, 1, 0}, second[3] = {1, 2, 2};
  const glm::dvec3& a = vertex[first[k]];
  const glm::dvec3& b = vertex[second[k]];
  const int sign = volume.directional != 0 ? -geometry::orientation_towards(a, b, p, light)
                                           : geometry::orientation(a, b, light, p);
  return volume.edge_outside[k] * sign > 0;
}

// ptsv::outside_plane.
__device__ inline bool outside_plane(const Volume& volume, int k, const glm::dvec3& p) {
  const gpu_ptsv::Plane& plane = volume.plane[k];
  const double value = plane_at(plane, p.x, p.y, p.z);
  const double ox = rounded_sub(p.x, plane.anchor[0]);
  const double oy = rounded_sub(p.y, plane.anchor[1]);
  const double oz = rounded_sub(p.z, plane.anchor[2]);
  const double bound = rounded_mul(rounded_mul(0x1p-44, rounded_add(1.0, volume.condition[k])),
                                   rounded_add(rounded_add(fabs(ox), fabs(oy)), fabs(oz)));
  if (value > bound) return true;
  if (value < -bound) return false;
  return outside_plane_exactly(volume, k, p);
}

// ptsv::sample_in_volume (the sample's own receiver aside).
__device__ inline bool sample_in_volume(const Volume& volume, std::uint32_t receiver,
                                        const glm::dvec3& p) {
  if (receiver == volume.triangle) return false;
  for (int k = 0; k < 3; ++k)
    if (outside_plane(volume, k, p)) return false;
  return !outside_plane(volume, 3, p);
}

}  // namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE::ptsv
