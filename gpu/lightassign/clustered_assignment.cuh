#pragma once
// Clustered light assignment (Paper II) on the device: per cluster its bounds (implicit: the tile
// x slice sub-frustum's box, grown by members outside it; explicit: the members' box) and normal
// cone (explicit from the members, or the normal cell's), then one warp per cluster traverses the
// light BVH and decides the leaves with the exact sphere/box cull and the back-face rule. Lists are
// written by count / exclusive scan / write, in Morton order within a list: the reference's lists.
#include <cstdint>

#include "gpu/emulator/kernel.h"
#include "gpu/kernel_progress.cuh"
#include "gpu/lightassign/device_buffer.cuh"
#include "gpu/lightassign/light_bvh.cuh"
#include "gpu/lightassign/lightassign_kernels.h"
#include "gpu/lightassign/view_frustum.cuh"
#include "shadowcts/geometry/normal_cone.h"
#include "shadowcts/geometry/sphere_box.h"

namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE::lightassign {

struct ClusterSettings {
  std::uint32_t tile_size = 32, tiles_x = 1, normal_divisions = 0;
  int bits_k = 0, bits_normal = 0;
  bool explicit_bounds = false, explicit_normal_cones = false;
};

// One thread per cluster, its members in ascending sample order (the order the reference grows
// the implicit box and sums the explicit cone's axis in, which both depend on).
__global__ void cluster_bounds(std::uint32_t clusters, const std::uint32_t* cluster_key,
                               const std::uint32_t* cluster_tile,
                               const std::uint32_t* member_offsets, const std::uint32_t* members,
                               const glm::vec3* position, const glm::vec3* normal,
                               const double* slice_near, const double* slice_far,
                               LightAssignFrame frame, ClusterSettings settings,
                               LightAssignBox* bounds, NormalCone* cones, std::uint32_t* grown) {
  const std::uint32_t c = blockIdx.x * blockDim.x + threadIdx.x;
  if (c >= clusters) return;
  const std::uint32_t first = member_offsets[c], last = member_offsets[c + 1];
  LightAssignBox box;
  std::uint32_t grew = 0;
  if (settings.explicit_bounds) {
    box.min = box.max = position[members[first]];
    for (std::uint32_t m = first + 1; m < last; ++m) grow_to_contain(box, position[members[m]]);
  } else {
    const std::uint32_t i = cluster_tile[c] % settings.tiles_x,
                        j = cluster_tile[c] / settings.tiles_x;
    SubFrustum f;
    f.x0 = double(i) * settings.tile_size;
    f.x1 = dmin(double(i + 1) * settings.tile_size, double(frame.width));
    f.y0 = double(j) * settings.tile_size;
    f.y1 = dmin(double(j + 1) * settings.tile_size, double(frame.height));
    f.near_depth = slice_near[c];
    f.far_depth = slice_far[c];
    box = bounding_box(frame, f);
    for (std::uint32_t m = first; m < last; ++m) grew += grow_to_contain(box, position[members[m]]);
  }
  bounds[c] = box;
  grown[c] = grew;
  NormalCone cone;
  if (settings.explicit_normal_cones) {
    geometry::ExplicitNormalConeSum sum;
    for (std::uint32_t m = first; m < last; ++m) sum.add_direction(normal[members[m]]);
    cone = sum.axis_only();
    for (std::uint32_t m = first; m < last; ++m)
      geometry::ExplicitNormalConeSum::widen(cone, normal[members[m]]);
  } else if (settings.normal_divisions > 0) {
    const std::uint32_t code =
        settings.bits_normal == 0 ? 0u : cluster_key[c] & ((1u << settings.bits_normal) - 1u);
    cone = geometry::normal_cell_cone(code, settings.normal_divisions);
  }
  cones[c] = cone;
}

// Work summed over all lists: nodes tested, lights tested, lights culled by the back-face rule.
struct WorkCounters {
  unsigned long long nodes_tested, light_tests, backface_culled;
};

// One warp per cluster: the BVH traversal and the cull. Count pass (lights == nullptr): each
// cluster's list length into count[c] and the work into `work`; write pass: the lights from
// offset[c] on.
__global__ void cluster_lights(std::uint32_t clusters, const LightAssignBox* bounds,
                               const NormalCone* cones, bool use_cones, BvhView bvh,
                               const LightAssignSphere* spheres, unsigned long long* count,
                               WorkCounters* work, const unsigned long long* offset,
                               std::uint32_t* lights, unsigned long long* blocks_started) {
  count_started_block(blocks_started);
  const std::uint32_t warp = (blockIdx.x * blockDim.x + threadIdx.x) / warpSize;
  const unsigned lane = threadIdx.x % warpSize;
  if (warp >= clusters) return;  // whole warps: the block is a multiple of 32
  const LightAssignBox box = bounds[warp];
  NormalCone cone;
  if (use_cones) cone = cones[warp];
  unsigned long long listed = 0, tests = 0, culled = 0;
  std::uint64_t position = lights == nullptr ? 0 : offset[warp];
  const std::uint64_t nodes =
      traverse_warp(bvh, box, lane, [&](std::uint32_t first, std::uint32_t n) {
        const std::uint32_t leaf = first + lane;
        const bool hit = lane < n && overlap(bvh.leaf_boxes[leaf], box);
        std::uint32_t light = 0;
        bool meets = false, behind = false;
        if (hit) {
          light = bvh.order[leaf];
          const LightAssignSphere s = spheres[light];
          meets = geometry::sphere_meets_box(s.centre, s.range, box.min, box.max);
          behind = meets && use_cones &&
                   geometry::light_behind_cone(cone, box.min, box.max, glm::dvec3(s.centre));
        }
        tests += bit_count(__ballot_sync(full_warp, hit));
        culled += bit_count(__ballot_sync(full_warp, behind));
        const unsigned accepted = __ballot_sync(full_warp, meets && !behind);
        if (lights != nullptr && meets && !behind)
          lights[position + bit_count(accepted & lanes_below(lane))] = light;
        position += bit_count(accepted);
        listed += bit_count(accepted);
      });
  if (lane != 0 || lights != nullptr) return;
  count[warp] = listed;
  atomicAdd(&work->nodes_tested, (unsigned long long)nodes);  // integer sums: any order
  atomicAdd(&work->light_tests, tests);
  atomicAdd(&work->backface_culled, culled);
}

}  // namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE::lightassign
