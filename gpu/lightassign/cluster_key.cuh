#pragma once
// Cluster keys of Paper II (Section 3.1) per sample on the device: view depth, screen tile,
// exponential depth slice (eq. 2 with the floor) and the quantized normal, packed as ClusterGrid
// (reference/lightassign/cluster_key.h) packs them, least significant first: normal, k, j, i.
//
// The device's log is not glibc's: where the quotient log(depth / near) / log(base) lies within
// 1e-10 (relative) of an integer, far above the few ulps by which the two can differ, the slice is
// marked doubtful and the host decides it with the reference's ClusterGrid::slice_of.
#include <cmath>
#include <cstdint>

#include "gpu/emulator/kernel.h"
#include "gpu/lightassign/device_buffer.cuh"
#include "gpu/lightassign/lightassign_kernels.h"
#include "gpu/lightassign/view_frustum.cuh"

namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE::lightassign {

// The view depth of every regular sample.
__global__ void sample_depths(std::uint32_t n, const glm::vec3* position, LightAssignFrame frame,
                              double* depth) {
  const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  depth[i] = view_depth(frame, position[i]);
}

// quantize_normal: cube face by the largest |component| (first on ties), X x X cells over it.
__device__ inline std::uint32_t quantize_normal(const glm::vec3& n, std::uint32_t divisions) {
  const double a[3] = {fabs(double(n.x)), fabs(double(n.y)), fabs(double(n.z))};
  int axis = 0;
  if (a[1] > a[axis]) axis = 1;
  if (a[2] > a[axis]) axis = 2;
  const std::uint32_t face = std::uint32_t(2 * axis + (n[axis] < 0.0f ? 1 : 0));
  if (!(a[axis] > 0.0)) return 0;
  const int u_axis = axis == 0 ? 1 : 0, v_axis = axis == 2 ? 1 : 2;
  auto cell = [&](int other) {
    const double t = rounded_mul(rounded_mul(rounded_add(double(n[other]) / a[axis], 1.0), 0.5),
                                 double(divisions));
    const double f = floor(t), top = double(divisions - 1);
    return std::uint32_t(f < 0.0 ? 0.0 : top < f ? top : f);
  };
  return face * divisions * divisions + cell(v_axis) * divisions + cell(u_axis);
}

// Per regular sample: its slice by the device's logarithm, and whether that is in doubt.
__global__ void sample_slices(std::uint32_t n, const double* depth, LightAssignGrid grid,
                              std::uint32_t* slice, std::uint8_t* doubtful) {
  const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  std::uint32_t k = 0;
  bool doubt = false;
  if (depth[i] > grid.near_plane) {
    const double q = log(depth[i] / grid.near_plane) / grid.log_base;
    const double f = floor(q), last = double(grid.slices - 1);
    k = std::uint32_t(f < last ? f : last);
    doubt = fabs(q - rint(q)) <= 1e-10 * (fabs(q) > 1.0 ? fabs(q) : 1.0);
  }
  slice[i] = k;
  doubtful[i] = doubt ? 1 : 0;
}

// Per regular sample: its packed key, and the sort key (tile << 32) | key that orders the samples
// by tile, then key, as the reference's unique clusters are numbered. Tiles (tile_only) have the
// constant key 0, as the reference's tiled variant gives them.
__global__ void sample_keys(std::uint32_t n, const std::uint32_t* pixel, const std::uint32_t* slice,
                            const glm::vec3* normal, LightAssignGrid grid, std::uint32_t width,
                            std::uint32_t tile_size, std::uint32_t normal_divisions, bool tile_only,
                            std::uint32_t* key, std::uint64_t* sort_key) {
  const std::uint32_t s = blockIdx.x * blockDim.x + threadIdx.x;
  if (s >= n) return;
  const std::uint32_t i = (pixel[s] % width) / tile_size, j = (pixel[s] / width) / tile_size;
  const std::uint32_t normal_code =
      normal_divisions > 0 ? quantize_normal(normal[s], normal_divisions) : 0;
  std::uint64_t packed = i;
  packed = (packed << grid.bits_j) | j;
  packed = (packed << grid.bits_k) | (tile_only ? 0u : slice[s]);
  packed = (packed << grid.bits_normal) | normal_code;
  if (tile_only) packed = 0;
  key[s] = std::uint32_t(packed);
  sort_key[s] = (std::uint64_t(j * grid.tiles_x + i) << 32) | std::uint32_t(packed);
}

}  // namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE::lightassign
