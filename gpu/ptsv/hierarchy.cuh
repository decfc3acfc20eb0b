#pragma once
// The view-sample cluster hierarchy on the device (the reference's hierarchy.h defines it): the
// regular samples sorted by key (a stable Thrust sort, so samples of one key stay in index order),
// then level by level from the leaves up the distinct key prefixes (head flags and a scan), the
// 32-bit child masks (each child ORs its bit into its parent), and the explicit bounds and reject
// reach: a leaf reduces its samples, an inner node its children.
//
// The boxes are min/max reductions, which do not depend on the order they are taken in except for
// the sign of a zero coordinate: the reference grows each box sample by sample in index order and
// keeps the first sample that reaches the extreme, so every reduction here keeps, among equal
// values, the one of the smallest sample index, and the boxes are the reference's bit for bit.
#include <cmath>
#include <cstdint>
#include <vector>

#include <thrust/count.h>
#include <thrust/execution_policy.h>
#include <thrust/scan.h>
#include <thrust/sequence.h>
#include <thrust/sort.h>

#include "gpu/emulator/kernel.h"
#include "gpu/ptsv/device_memory.cuh"
#include "gpu/ptsv/ptsv_kernels.h"

namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE::ptsv {

// Explicit bounds of a node, with the sample each extreme comes from (for the ties).
struct NodeBox {
  double lo[3], hi[3];
  std::uint32_t lo_sample[3], hi_sample[3];
  double reach;
};

__device__ inline std::uint32_t key_prefix(std::uint32_t key, int shift) {
  return shift >= 32 ? 0u : key >> shift;
}

__device__ inline void grow(NodeBox& box, const double value[3], const std::uint32_t lo_sample[3],
                            const double high[3], const std::uint32_t hi_sample[3], double reach) {
  for (int k = 0; k < 3; ++k) {
    if (value[k] < box.lo[k] || (value[k] == box.lo[k] && lo_sample[k] < box.lo_sample[k])) {
      box.lo[k] = value[k];
      box.lo_sample[k] = lo_sample[k];
    }
    if (high[k] > box.hi[k] || (high[k] == box.hi[k] && hi_sample[k] < box.hi_sample[k])) {
      box.hi[k] = high[k];
      box.hi_sample[k] = hi_sample[k];
    }
  }
  if (box.reach < reach) box.reach = reach;  // std::max(reach, sample reach)
}

__device__ inline NodeBox empty_box() {
  NodeBox box;
  for (int k = 0; k < 3; ++k) {
    box.lo[k] = HUGE_VAL;
    box.hi[k] = -HUGE_VAL;
    box.lo_sample[k] = box.hi_sample[k] = gpu_ptsv::no_sample;
  }
  box.reach = 0.0;
  return box;
}

// flags[i]: sorted key i starts a node of the level (its prefix differs from the previous one).
__global__ void node_heads(const std::uint32_t* sorted_keys, std::uint32_t n, int shift,
                           std::uint32_t* flags) {
  const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  flags[i] = i == 0 || key_prefix(sorted_keys[i], shift) != key_prefix(sorted_keys[i - 1], shift)
                 ? 1u
                 : 0u;
}

// node_of[i]: 1 + the node of sorted sample i (inclusive scan of the heads).
__global__ void node_starts(const std::uint32_t* sorted_keys, const std::uint32_t* flags,
                            const std::uint32_t* node_of, std::uint32_t n, int shift,
                            std::uint32_t* index, std::uint32_t* first_sample) {
  const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n || flags[i] == 0) return;
  const std::uint32_t node = node_of[i] - 1;
  index[node] = key_prefix(sorted_keys[i], shift);
  first_sample[node] = i;
}

// For each node c of level l + 1: its parent in level l, the parent's child-mask bit and, for the
// first child of a parent, the parent's first_child.
__global__ void link_children(const std::uint32_t* child_index, const std::uint32_t* child_first,
                              std::uint32_t child_count, const std::uint32_t* parent_node_of,
                              std::uint32_t* parent, std::uint32_t* child_mask,
                              std::uint32_t* first_child) {
  const std::uint32_t c = blockIdx.x * blockDim.x + threadIdx.x;
  if (c >= child_count) return;
  const std::uint32_t p = parent_node_of[child_first[c]] - 1;
  parent[c] = p;
  atomicOr(&child_mask[p], 1u << (child_index[c] & 31u));
  if (c == 0 || parent_node_of[child_first[c - 1]] - 1 != p) first_child[p] = c;
}

__global__ void leaf_bounds(const std::uint32_t* first_sample, std::uint32_t count,
                            const std::uint32_t* sorted_samples, const gpu_ptsv::Sample* samples,
                            NodeBox* boxes) {
  const std::uint32_t p = blockIdx.x * blockDim.x + threadIdx.x;
  if (p >= count) return;
  NodeBox box = empty_box();
  for (std::uint32_t i = first_sample[p]; i < first_sample[p + 1]; ++i) {
    const std::uint32_t s = sorted_samples[i];
    const gpu_ptsv::Sample sample = samples[s];
    const double position[3] = {double(sample.position[0]), double(sample.position[1]),
                                double(sample.position[2])};
    const std::uint32_t index[3] = {s, s, s};
    grow(box, position, index, position, index, sample.reach);
  }
  boxes[p] = box;
}

__global__ void inner_bounds(const std::uint32_t* first_child, std::uint32_t count,
                             const NodeBox* child_boxes, NodeBox* boxes) {
  const std::uint32_t p = blockIdx.x * blockDim.x + threadIdx.x;
  if (p >= count) return;
  NodeBox box = empty_box();
  for (std::uint32_t c = first_child[p]; c < first_child[p + 1]; ++c) {
    const NodeBox child = child_boxes[c];
    grow(box, child.lo, child.lo_sample, child.hi, child.hi_sample, child.reach);
  }
  boxes[p] = box;
}

struct DeviceLevel {
  std::uint32_t count = 0;
  DeviceArray<std::uint32_t> index, child_mask, first_sample, first_child, parent, node_of;
  DeviceArray<NodeBox> box;
};

struct DeviceHierarchy {
  std::uint32_t regular = 0;  // samples with a key
  DeviceArray<std::uint32_t> sorted_keys, sorted_samples;
  std::vector<DeviceLevel> levels;  // 0 .. leaf level
};

// keys: per view sample (no_key: none), on the device.
inline DeviceHierarchy build_hierarchy(const DeviceArray<std::uint32_t>& keys,
                                       const DeviceArray<gpu_ptsv::Sample>& samples,
                                       std::uint32_t sample_count, int leaf_level,
                                       LaunchCount& launches) {
  DeviceHierarchy h;
  h.sorted_keys.resize(sample_count);
  h.sorted_samples.resize(sample_count);
  if (sample_count != 0) {
    check(cudaMemcpy(h.sorted_keys.data(), keys.data(), sample_count * sizeof(std::uint32_t),
                     cudaMemcpyDeviceToDevice),
          "cudaMemcpy");
    thrust::sequence(thrust::device, h.sorted_samples.data(),
                     h.sorted_samples.data() + sample_count);
    thrust::stable_sort_by_key(thrust::device, h.sorted_keys.data(),
                               h.sorted_keys.data() + sample_count, h.sorted_samples.data());
    h.regular = sample_count -
                std::uint32_t(thrust::count(thrust::device, h.sorted_keys.data(),
                                            h.sorted_keys.data() + sample_count, gpu_ptsv::no_key));
  }
  const std::uint32_t n = h.regular;
  h.levels.resize(std::size_t(leaf_level) + 1);
  DeviceArray<std::uint32_t> flags(n);
  for (int l = leaf_level; l >= 0; --l) {
    DeviceLevel& level = h.levels[std::size_t(l)];
    const int shift = 5 * (leaf_level - l);
    level.node_of.resize(n);
    if (n != 0) {
      SHADOWCTS_LAUNCH(node_heads, launches.blocks(n), threads_per_block, 0)
      (h.sorted_keys.data(), n, shift, flags.data());
      after_launch("node_heads");
      thrust::inclusive_scan(thrust::device, flags.data(), flags.data() + n, level.node_of.data());
      level.count = level.node_of.at(n - 1);
    }
    // The root exists without samples too.
    const bool empty_root = l == 0 && n == 0;
    if (empty_root) level.count = 1;
    level.index.resize(level.count);
    level.first_sample.resize(level.count + 1);
    level.child_mask.resize(level.count);
    level.child_mask.zero();
    level.first_child.resize(level.count + 1);
    level.box.resize(level.count);
    if (empty_root) {
      level.index.set(0, 0u);
      level.first_sample.set(0, 0u);
      level.first_child.set(0, 0u);
    } else if (n != 0) {  // a grid of no blocks is an invalid launch on a device
      SHADOWCTS_LAUNCH(node_starts, launches.blocks(n), threads_per_block, 0)
      (h.sorted_keys.data(), flags.data(), level.node_of.data(), n, shift, level.index.data(),
       level.first_sample.data());
      after_launch("node_starts");
    }
    level.first_sample.set(level.count, n);
  }
  for (int l = leaf_level; l >= 0; --l) {
    DeviceLevel& level = h.levels[std::size_t(l)];
    if (l < leaf_level) {
      DeviceLevel& below = h.levels[std::size_t(l) + 1];
      below.parent.resize(below.count);
      if (below.count != 0) {
        SHADOWCTS_LAUNCH(link_children, launches.blocks(below.count), threads_per_block, 0)
        (below.index.data(), below.first_sample.data(), below.count, level.node_of.data(),
         below.parent.data(), level.child_mask.data(), level.first_child.data());
        after_launch("link_children");
      }
      level.first_child.set(level.count, below.count);
      if (level.count != 0) {
        SHADOWCTS_LAUNCH(inner_bounds, launches.blocks(level.count), threads_per_block, 0)
        (level.first_child.data(), level.count, below.box.data(), level.box.data());
        after_launch("inner_bounds");
      }
    } else if (level.count != 0) {
      SHADOWCTS_LAUNCH(leaf_bounds, launches.blocks(level.count), threads_per_block, 0)
      (level.first_sample.data(), level.count, h.sorted_samples.data(), samples.data(),
       level.box.data());
      after_launch("leaf_bounds");
    }
  }
  return h;
}

}  // namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE::ptsv
