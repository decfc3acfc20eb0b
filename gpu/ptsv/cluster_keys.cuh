#pragma once
// Cluster keys on the device (the reference's cluster_keys.h defines them): one thread per view
// sample. The view depth and screen coordinates are evaluated with one rounding per operation in
// the reference's order (no FMA), and the depth slice is looked up in the host's table of slice
// starts (the reference's std::pow values), so every key is the reference's bit for bit.
#include <cstdint>

#include "gpu/emulator/kernel.h"
#include "gpu/ptsv/ptsv_kernels.h"
#include "shadowcts/geometry/rounded_arithmetic.h"

namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE::ptsv {

using gpu_ptsv::Layout;

__device__ inline double dot3(const double a[3], const double b[3]) {
  return rounded_add(rounded_add(rounded_mul(a[0], b[0]), rounded_mul(a[1], b[1])),
                     rounded_mul(a[2], b[2]));
}

// ptsv::screen_x_of_column / screen_y_of_row.
__device__ inline double screen_x_of_column(const Layout& f, double x) {
  return rounded_mul(rounded_mul(rounded_sub(2.0 * x / double(f.width), 1.0), f.tan_half_fov),
                     f.aspect);
}
__device__ inline double screen_y_of_row(const Layout& f, double y) {
  return rounded_mul(rounded_sub(1.0, 2.0 * y / double(f.height)), f.tan_half_fov);
}

// ptsv::ClusterKeyLayout::interleave.
__device__ inline std::uint32_t interleave(const Layout& layout, std::uint32_t x, std::uint32_t y,
                                           std::uint32_t slice) {
  std::uint32_t key = 0;
  int position = 0;
  int most = layout.x_bits > layout.y_bits ? layout.x_bits : layout.y_bits;
  if (layout.depth_bits > most) most = layout.depth_bits;
  for (int bit = 0; bit < most; ++bit) {
    if (bit < layout.x_bits) key |= ((x >> bit) & 1u) << position++;
    if (bit < layout.y_bits) key |= ((y >> bit) & 1u) << position++;
    if (bit < layout.depth_bits) key |= ((slice >> bit) & 1u) << position++;
  }
  return key;
}

// ptsv::ClusterKeyLayout::deinterleave.
__device__ inline void deinterleave(const Layout& layout, std::uint32_t key, std::uint32_t& x,
                                    std::uint32_t& y, std::uint32_t& slice) {
  x = y = slice = 0;
  int position = 0;
  int most = layout.x_bits > layout.y_bits ? layout.x_bits : layout.y_bits;
  if (layout.depth_bits > most) most = layout.depth_bits;
  for (int bit = 0; bit < most; ++bit) {
    if (bit < layout.x_bits) x |= ((key >> position++) & 1u) << bit;
    if (bit < layout.y_bits) y |= ((key >> position++) & 1u) << bit;
    if (bit < layout.depth_bits) slice |= ((key >> position++) & 1u) << bit;
  }
}

// The key of every regular sample (no_key for the others) and its 8x8 tile (row-major); the
// lowest sample the layout cannot hold goes to *first_bad.
__global__ void assign_cluster_keys(const gpu_ptsv::Sample* samples, std::uint32_t count,
                                    Layout layout, const double* slice_start, bool require_wedge,
                                    std::uint32_t* keys, std::uint32_t* tiles,
                                    std::uint32_t* first_bad) {
  const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= count) return;
  const gpu_ptsv::Sample s = samples[i];
  keys[i] = gpu_ptsv::no_key;
  tiles[i] = gpu_ptsv::no_key;
  if (s.regular == 0) return;
  double d[3];
  for (int k = 0; k < 3; ++k) d[k] = rounded_sub(double(s.position[k]), layout.origin[k]);
  const double depth = dot3(d, layout.forward);
  if (!(depth > 0.0)) {
    atomicMin(first_bad, i);
    return;
  }
  const std::uint32_t tx = s.pixel_x / 8, ty = s.pixel_y / 8;
  // ClusterKeyLayout::slice_of_depth: the k with slice_start(k) <= depth < slice_start(k + 1);
  // k = 2^depth_bits means beyond the last slice.
  const std::uint32_t limit = 1u << layout.depth_bits;
  std::uint32_t low = 0, high = limit;  // slice_start[low] <= depth (slice_start[0] = 0)
  while (low < high) {
    const std::uint32_t mid = low + (high - low + 1) / 2;
    if (slice_start[mid] <= depth) {
      low = mid;
    } else {
      high = mid - 1;
    }
  }
  if (tx >= layout.tiles_x || ty >= layout.tiles_y || low >= limit) {
    atomicMin(first_bad, i);
    return;
  }
  if (require_wedge) {
    // ptsv::inside_pixel_wedge of the sample's tile.
    const double sx = dot3(d, layout.right) / depth, sy = dot3(d, layout.up) / depth;
    const bool inside = sx >= screen_x_of_column(layout, double(tx * 8)) &&
                        sx <= screen_x_of_column(layout, double((tx + 1) * 8)) &&
                        sy <= screen_y_of_row(layout, double(ty * 8)) &&
                        sy >= screen_y_of_row(layout, double((ty + 1) * 8));
    if (!inside) {
      atomicMin(first_bad, i);
      return;
    }
  }
  keys[i] = interleave(layout, tx, ty, low);
  tiles[i] = ty * layout.tiles_x + tx;
}

}  // namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE::ptsv
