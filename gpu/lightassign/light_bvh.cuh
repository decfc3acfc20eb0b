#pragma once
// Paper II's light hierarchy (Sections 3.3, 4.4) built and traversed on the device, by the
// definition of reference/lightassign/light_bvh.h: lights sorted by the Morton code of their
// centres (21 bits per axis over the box around all centres; a stable Thrust sort of the codes
// with the light indices ascending is the reference's sort of (code, index) pairs), leaves the
// float boxes of the spheres rounded outwards, 32 consecutive children per node up to one root.
// A warp traverses it for one query box: the 32 children of a node are tested by the 32 lanes
// and __ballot_sync gives the overlapping ones; descending into the lowest set bit first visits
// the leaves in Morton order, as the reference's depth-first stack does, and counts the same
// node tests.
#include <cstdint>
#include <vector>

#include <thrust/execution_policy.h>
#include <thrust/functional.h>
#include <thrust/sequence.h>
#include <thrust/sort.h>
#include <thrust/transform_reduce.h>

#include "gpu/emulator/kernel.h"
#include "gpu/lightassign/device_buffer.cuh"
#include "gpu/lightassign/lightassign_kernels.h"
#include "gpu/lightassign/view_frustum.cuh"
#include "shadowcts/geometry/morton.h"

namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE::lightassign {

constexpr std::uint32_t bvh_branching = 32;  // LightBvh::branching, one child per lane
constexpr int bvh_max_levels = 8;            // 32^7 > 2^32 lights

// What a traversal reads: the boxes of every level in one array, level 0 (over the leaves) first.
struct BvhView {
  const LightAssignBox* leaf_boxes = nullptr;
  const std::uint32_t* order = nullptr;  // leaf -> light index
  const LightAssignBox* nodes = nullptr;
  std::uint32_t leaf_count = 0;
  int top = -1;  // the root's level; -1 without lights
  std::uint32_t level_offset[bvh_max_levels] = {}, level_size[bvh_max_levels] = {};
};

__device__ inline bool overlap(const LightAssignBox& a, const LightAssignBox& b) {
  return a.min.x <= b.max.x && b.min.x <= a.max.x && a.min.y <= b.max.y && b.min.y <= a.max.y &&
         a.min.z <= b.max.z && b.min.z <= a.max.z;
}

struct CentreCoordinate {
  int axis;
  __host__ __device__ double operator()(const LightAssignSphere& l) const {
    return double(l.centre[axis]);
  }
};

__global__ void morton_codes(std::uint32_t n, const LightAssignSphere* lights, glm::dvec3 low,
                             glm::dvec3 extent, std::uint64_t* code) {
  const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  std::uint64_t c = 0;
  for (int k = 0; k < 3; ++k) {
    const double t = rounded_sub(double(lights[i].centre[k]), low[k]) / extent[k];
    const double scaled = rounded_mul(t, 2097152.0);
    const double q = scaled < 0.0 ? 0.0 : 2097151.0 < scaled ? 2097151.0 : scaled;  // std::clamp
    c |= shadowcts::geometry::spread_bits_21(std::uint64_t(q)) << (2 - k);
  }
  code[i] = c;
}

__global__ void leaf_boxes(std::uint32_t n, const LightAssignSphere* lights,
                           const std::uint32_t* order, LightAssignBox* box) {
  const std::uint32_t leaf = blockIdx.x * blockDim.x + threadIdx.x;
  if (leaf >= n) return;
  const LightAssignSphere l = lights[order[leaf]];
  LightAssignBox b;
  for (int k = 0; k < 3; ++k) {
    b.min[k] = round_down(rounded_sub(double(l.centre[k]), double(l.range)));
    b.max[k] = round_up(rounded_add(double(l.centre[k]), double(l.range)));
  }
  box[leaf] = b;
}

// One thread per node: the box around its (up to) 32 children.
__global__ void node_boxes(std::uint32_t nodes, const LightAssignBox* children,
                           std::uint32_t child_count, LightAssignBox* box) {
  const std::uint32_t node = blockIdx.x * blockDim.x + threadIdx.x;
  if (node >= nodes) return;
  const std::uint32_t first = node * bvh_branching;
  const std::uint32_t last =
      child_count - first < bvh_branching ? child_count : first + bvh_branching;
  LightAssignBox b = children[first];
  for (std::uint32_t c = first + 1; c < last; ++c) {
    const LightAssignBox child = children[c];
    for (int k = 0; k < 3; ++k) {
      if (child.min[k] < b.min[k]) b.min[k] = child.min[k];  // glm::min's choice
      if (b.max[k] < child.max[k]) b.max[k] = child.max[k];
    }
  }
  box[node] = b;
}

class DeviceLightBvh {
 public:
  DeviceLightBvh(const DeviceArray<LightAssignSphere>& lights, Launches& launches) {
    const auto n = std::uint32_t(lights.size());
    view_.leaf_count = n;
    if (n == 0) return;
    const LightAssignSphere* first = lights.data();
    glm::dvec3 low, high, extent;
    for (int k = 0; k < 3; ++k) {
      low[k] = thrust::transform_reduce(thrust::device, first, first + n, CentreCoordinate{k},
                                        double(INFINITY), thrust::minimum<double>());
      high[k] = thrust::transform_reduce(thrust::device, first, first + n, CentreCoordinate{k},
                                         -double(INFINITY), thrust::maximum<double>());
      const double e = high[k] - low[k];
      extent[k] = e < 1e-300 ? 1e-300 : e;  // glm::max(high - low, 1e-300)
    }
    DeviceArray<std::uint64_t> codes(n);
    order_.resize(n);
    SHADOWCTS_LAUNCH(morton_codes, launches.blocks_for(n, threads_per_block), threads_per_block, 0)
    (n, first, low, extent, codes.data());
    Launches::finish("morton_codes");
    thrust::sequence(thrust::device, order_.data(), order_.data() + n, 0u);
    thrust::stable_sort_by_key(thrust::device, codes.data(), codes.data() + n, order_.data());
    leaves_.resize(n);
    SHADOWCTS_LAUNCH(leaf_boxes, launches.blocks_for(n, threads_per_block), threads_per_block, 0)
    (n, first, order_.data(), leaves_.data());
    Launches::finish("leaf_boxes");

    // Levels of 32 consecutive children each, until one root.
    std::vector<std::uint32_t> sizes;
    for (std::uint32_t count = n; sizes.empty() || count > 1;) {
      count = (count + bvh_branching - 1) / bvh_branching;
      sizes.push_back(count);
    }
    std::uint32_t total = 0;
    for (std::size_t l = 0; l < sizes.size(); ++l) {
      view_.level_offset[l] = total;
      view_.level_size[l] = sizes[l];
      total += sizes[l];
    }
    nodes_.resize(total);
    for (std::size_t l = 0; l < sizes.size(); ++l) {
      const LightAssignBox* children =
          l == 0 ? leaves_.data() : nodes_.data() + view_.level_offset[l - 1];
      const std::uint32_t child_count = l == 0 ? n : sizes[l - 1];
      SHADOWCTS_LAUNCH(node_boxes, launches.blocks_for(sizes[l], threads_per_block),
                       threads_per_block, 0)
      (sizes[l], children, child_count, nodes_.data() + view_.level_offset[l]);
      Launches::finish("node_boxes");
    }
    view_.top = int(sizes.size()) - 1;
    view_.leaf_boxes = leaves_.data();
    view_.order = order_.data();
    view_.nodes = nodes_.data();
  }

  const BvhView& view() const { return view_; }
  const DeviceArray<std::uint32_t>& order() const { return order_; }

 private:
  DeviceArray<std::uint32_t> order_;
  DeviceArray<LightAssignBox> leaves_, nodes_;
  BvhView view_;
};

// Depth-first traversal by one whole warp for `box` (the same in every lane): calls
// leaves(first_leaf, count) in every lane for each level-0 node whose ancestors' boxes all overlap
// the box, in Morton order (lane l holds leaf first_leaf + l when l < count). Returns the node
// boxes tested, as LightBvh::traverse counts them (the root, every child of an expanded node,
// every leaf of a visited level-0 node).
template <class Leaves>
__device__ std::uint64_t traverse_warp(const BvhView& bvh, const LightAssignBox& box, unsigned lane,
                                       Leaves&& leaves) {
  if (bvh.top < 0) return 0;
  std::uint64_t tested = 1;
  if (!overlap(bvh.nodes[bvh.level_offset[bvh.top]], box)) return tested;
  // Per level: the node being expanded and its overlapping children not yet visited.
  std::uint32_t node_at[bvh_max_levels];
  unsigned pending[bvh_max_levels];
  int level = bvh.top;
  node_at[level] = 0;
  for (;;) {
    const std::uint32_t first = node_at[level] * bvh_branching;
    if (level == 0) {
      const std::uint32_t rest = bvh.leaf_count - first;
      const std::uint32_t count = rest < bvh_branching ? rest : bvh_branching;
      tested += count;
      leaves(first, count);
      level = 1;
    } else {
      const std::uint32_t rest = bvh.level_size[level - 1] - first;
      const std::uint32_t count = rest < bvh_branching ? rest : bvh_branching;
      tested += count;
      const bool hit =
          lane < count && overlap(bvh.nodes[bvh.level_offset[level - 1] + first + lane], box);
      pending[level] = __ballot_sync(full_warp, hit);
    }
    while (level <= bvh.top && pending[level] == 0) ++level;
    if (level > bvh.top) break;
    const unsigned lowest = pending[level] & (~pending[level] + 1u);
    pending[level] &= pending[level] - 1u;
    const std::uint32_t child = node_at[level] * bvh_branching + bit_count(lowest - 1u);
    --level;
    node_at[level] = child;
  }
  return tested;
}

}  // namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE::lightassign
