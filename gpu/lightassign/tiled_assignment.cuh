#pragma once
// Tiled light assignment (Paper I) on the device: per occupied tile the min/max view depth of its
// samples by a block-wide reduction in shared memory, the sub-frustum's declared box; per light
// the tiles its screen rectangle covers, as (tile list, light) pairs written by count / exclusive
// scan / write and grouped by a stable sort (each tile's candidates stay in light order); then one
// warp per tile tests 32 candidates at a time against the sub-frustum planes and, exactly, the box.
#include <cstdint>

#include "gpu/emulator/kernel.h"
#include "gpu/lightassign/device_buffer.cuh"
#include "gpu/lightassign/light_bvh.cuh"
#include "gpu/lightassign/lightassign_kernels.h"
#include "gpu/lightassign/view_frustum.cuh"
#include "shadowcts/geometry/sphere_box.h"

namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE::lightassign {

constexpr std::uint32_t no_list = 0xFFFFFFFFu;

// One block per occupied tile.
__global__ void tile_volumes(std::uint32_t tiles, const std::uint32_t* tile_of_list,
                             const std::uint32_t* member_offsets, const std::uint32_t* members,
                             const double* depth, const glm::vec3* position, LightAssignFrame frame,
                             std::uint32_t tile_size, std::uint32_t tiles_x, SubFrustum* sub_frusta,
                             LightAssignBox* bounds, std::uint32_t* grown,
                             std::uint32_t* list_of_tile) {
  // Per thread: the min and max depth of its members, and of each position coordinate (to see
  // whether any member can grow the box).
  SHADOWCTS_SHARED(double[2 * threads_per_block], depth_range);
  SHADOWCTS_SHARED(float[6 * threads_per_block], position_range);
  const std::uint32_t t = blockIdx.x;
  if (t >= tiles) return;  // the whole block
  const unsigned me = threadIdx.x;
  const std::uint32_t first = member_offsets[t], last = member_offsets[t + 1];
  double near_depth = INFINITY, far_depth = -INFINITY;
  float low[3] = {INFINITY, INFINITY, INFINITY}, high[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (std::uint32_t m = first + me; m < last; m += threads_per_block) {
    const std::uint32_t s = members[m];
    near_depth = dmin(near_depth, depth[s]);
    far_depth = dmax(far_depth, depth[s]);
    const glm::vec3 p = position[s];
    for (int a = 0; a < 3; ++a) {
      low[a] = p[a] < low[a] ? p[a] : low[a];
      high[a] = high[a] < p[a] ? p[a] : high[a];
    }
  }
  depth_range[me] = near_depth;
  depth_range[threads_per_block + me] = far_depth;
  for (int a = 0; a < 3; ++a) {
    position_range[a * threads_per_block + me] = low[a];
    position_range[(3 + a) * threads_per_block + me] = high[a];
  }
  __syncthreads();
  for (unsigned half = threads_per_block / 2; half > 0; half /= 2) {
    if (me < half) {
      depth_range[me] = dmin(depth_range[me], depth_range[me + half]);
      depth_range[threads_per_block + me] =
          dmax(depth_range[threads_per_block + me], depth_range[threads_per_block + me + half]);
      for (int a = 0; a < 3; ++a) {
        const float l = position_range[a * threads_per_block + me + half];
        if (l < position_range[a * threads_per_block + me])
          position_range[a * threads_per_block + me] = l;
        const float h = position_range[(3 + a) * threads_per_block + me + half];
        if (position_range[(3 + a) * threads_per_block + me] < h)
          position_range[(3 + a) * threads_per_block + me] = h;
      }
    }
    __syncthreads();
  }
  if (me != 0) return;
  // min/max are exact in any order: the reference's depth range.
  const std::uint32_t tile = tile_of_list[t];
  SubFrustum f;
  f.x0 = double(tile % tiles_x) * tile_size;
  f.x1 = dmin(f.x0 + tile_size, double(frame.width));
  f.y0 = double(tile / tiles_x) * tile_size;
  f.y1 = dmin(f.y0 + tile_size, double(frame.height));
  f.near_depth = depth_range[0];
  f.far_depth = depth_range[threads_per_block];
  LightAssignBox box = bounding_box(frame, f);
  bool inside = true;
  for (int a = 0; a < 3; ++a)
    inside = inside && !(position_range[a * threads_per_block] < box.min[a]) &&
             !(position_range[(3 + a) * threads_per_block] > box.max[a]);
  std::uint32_t grew = 0;
  // Members inside the box cannot grow it; otherwise grow in member order, as the reference
  // counts (rare: the box has a rounding margin).
  if (!inside)
    for (std::uint32_t m = first; m < last; ++m) grew += grow_to_contain(box, position[members[m]]);
  sub_frusta[t] = f;
  bounds[t] = box;
  grown[t] = grew;
  list_of_tile[tile] = t;
}

// Per light: the tiles its screen rectangle covers, and how many of them are occupied.
__global__ void light_rects(std::uint32_t n, const LightAssignSphere* lights,
                            LightAssignFrame frame, std::uint32_t tile_size, std::uint32_t tiles_x,
                            std::uint32_t tiles_y, const std::uint32_t* list_of_tile,
                            TileRect* rects, unsigned long long* count) {
  const std::uint32_t l = blockIdx.x * blockDim.x + threadIdx.x;
  if (l >= n) return;
  const TileRect rect = covered_tiles(frame, lights[l], tile_size, tiles_x, tiles_y);
  unsigned long long occupied = 0;
  for (std::uint32_t y = rect.y0; y <= rect.y1 && rect.x0 <= rect.x1; ++y)
    for (std::uint32_t x = rect.x0; x <= rect.x1; ++x)
      occupied += list_of_tile[y * tiles_x + x] != no_list;
  rects[l] = rect;
  count[l] = occupied;
}

__global__ void light_pairs(std::uint32_t n, const TileRect* rects, std::uint32_t tiles_x,
                            const std::uint32_t* list_of_tile, const unsigned long long* offset,
                            std::uint32_t* pair_list, std::uint32_t* pair_light) {
  const std::uint32_t l = blockIdx.x * blockDim.x + threadIdx.x;
  if (l >= n) return;
  const TileRect rect = rects[l];
  unsigned long long at = offset[l];
  for (std::uint32_t y = rect.y0; y <= rect.y1 && rect.x0 <= rect.x1; ++y)
    for (std::uint32_t x = rect.x0; x <= rect.x1; ++x)
      if (const std::uint32_t list = list_of_tile[y * tiles_x + x]; list != no_list) {
        pair_list[at] = list;
        pair_light[at] = l;
        ++at;
      }
}

// One warp per tile, 32 candidates at a time. Count pass (lights == nullptr) and write pass as
// cluster_lights.
__global__ void tile_lights(std::uint32_t tiles, const unsigned long long* candidate_offset,
                            const std::uint32_t* candidates, const SubFrustum* sub_frusta,
                            const LightAssignBox* bounds, const LightAssignSphere* spheres,
                            LightAssignFrame frame, unsigned long long* count,
                            const unsigned long long* offset, std::uint32_t* lights) {
  const std::uint32_t warp = (blockIdx.x * blockDim.x + threadIdx.x) / warpSize;
  const unsigned lane = threadIdx.x % warpSize;
  if (warp >= tiles) return;  // whole warps
  const SubFrustum f = sub_frusta[warp];
  const LightAssignBox box = bounds[warp];
  unsigned long long position = lights == nullptr ? 0 : offset[warp];
  for (unsigned long long e = candidate_offset[warp]; e < candidate_offset[warp + 1];
       e += warpSize) {
    bool pass = false;
    std::uint32_t light = 0;
    if (e + lane < candidate_offset[warp + 1]) {
      light = candidates[e + lane];
      const LightAssignSphere s = spheres[light];
      pass = sphere_may_meet(frame, f, glm::dvec3(s.centre), double(s.range)) &&
             geometry::sphere_meets_box(s.centre, s.range, box.min, box.max);
    }
    const unsigned accepted = __ballot_sync(full_warp, pass);
    if (lights != nullptr && pass)
      lights[position + bit_count(accepted & lanes_below(lane))] = light;
    position += bit_count(accepted);
  }
  if (lane == 0 && lights == nullptr) count[warp] = position;
}

}  // namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE::lightassign
