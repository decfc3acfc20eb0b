#pragma once
// The CUDA ptsv, written once (gpu/emulator/kernel.h): nvcc builds it into the `cuda` backend, the
// host compiler into `cuda-emu` against the emulator. Cluster keys (cluster_keys.cuh), the
// hierarchy from a Thrust sort of the keys (hierarchy.cuh), the samples of each 8x8 tile (a
// second stable sort), and the traversal (traversal.cuh).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include <thrust/binary_search.h>
#include <thrust/execution_policy.h>
#include <thrust/functional.h>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/reduce.h>
#include <thrust/sequence.h>
#include <thrust/sort.h>

#include "gpu/emulator/kernel.h"
#include "gpu/ptsv/cluster_keys.cuh"
#include "gpu/ptsv/device_memory.cuh"
#include "gpu/ptsv/hierarchy.cuh"
#include "gpu/ptsv/node_test.cuh"
#include "gpu/ptsv/ptsv_kernels.h"
#include "gpu/ptsv/traversal.cuh"

namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE::ptsv {

// The largest |coordinate| of each node's implicit cell (the reference's implicit_corner_bound
// takes the largest over level 1, whose cells contain all deeper ones).
__global__ void cell_corner_bounds(const std::uint32_t* index, std::uint32_t count, Layout layout,
                                   const double* slice_start, int level, double* bound) {
  const std::uint32_t c = blockIdx.x * blockDim.x + threadIdx.x;
  if (c >= count) return;
  const CellCorners corners = implicit_cell_corners(layout, slice_start, level, index[c]);
  double largest = 0.0;
  for (int i = 0; i < 8; ++i)
    for (int k = 0; k < 3; ++k) largest = fmax(largest, fabs(corners.p[i][k]));
  bound[c] = largest;
}

// Takes the input by value: each host array is freed once uploaded.
inline gpu_ptsv::KernelResult run(gpu_ptsv::KernelInput in) {
  if (in.samples.size() >= gpu_ptsv::no_sample || in.volumes.size() >= 0xFFFFFFFFu)
    throw std::length_error("ptsv: more than 2^32 - 1 view samples or volumes");
  if (in.slice_start.size() != (std::size_t(1) << in.layout.depth_bits) + 1)
    throw std::invalid_argument("ptsv: one slice start per depth slice and one past them");
  const auto count = std::uint32_t(in.samples.size());
  LaunchCount launches;
  gpu_ptsv::KernelResult result;

  const DeviceArray<gpu_ptsv::Sample> samples = upload_and_free(in.samples);
  const DeviceArray<double> slice_start = upload_and_free(in.slice_start);
  DeviceArray<std::uint32_t> keys(count), tiles(count), first_bad(1);
  first_bad.set(0, gpu_ptsv::no_sample);
  if (count != 0) {
    SHADOWCTS_LAUNCH(assign_cluster_keys, launches.blocks(count), threads_per_block, 0)
    (samples.data(), count, in.layout, slice_start.data(), in.implicit_cells, keys.data(),
     tiles.data(), first_bad.data());
    after_launch("assign_cluster_keys");
  }
  result.first_bad_sample = first_bad.at(0);
  result.threads = launches.threads;
  if (result.first_bad_sample != gpu_ptsv::no_sample) return result;

  DeviceHierarchy h = build_hierarchy(keys, samples, count, in.layout.leaf_level, launches);

  // The regular samples of each tile in index order: a stable sort by tile, then each tile's
  // first position by a vectorized binary search.
  const std::uint32_t tile_count = in.layout.tiles_x * in.layout.tiles_y;
  DeviceArray<std::uint32_t> tile_samples(count), tile_offsets(std::size_t(tile_count) + 1);
  if (count != 0) {
    thrust::sequence(thrust::device, tile_samples.data(), tile_samples.data() + count);
    thrust::stable_sort_by_key(thrust::device, tiles.data(), tiles.data() + count,
                               tile_samples.data());
  }
  thrust::lower_bound(thrust::device, tiles.data(), tiles.data() + count,
                      thrust::counting_iterator<std::uint32_t>(0),
                      thrust::counting_iterator<std::uint32_t>(tile_count + 1),
                      tile_offsets.data());

  // NodeTolerances::for_bounds(node bound, scene bound).
  double node_bound = in.scene_bound;
  if (in.implicit_cells) {
    const int level = in.layout.leaf_level < 1 ? in.layout.leaf_level : 1;
    const DeviceLevel& cells = h.levels[std::size_t(level)];
    DeviceArray<double> bounds(cells.count);
    if (cells.count != 0) {
      SHADOWCTS_LAUNCH(cell_corner_bounds, launches.blocks(cells.count), threads_per_block, 0)
      (cells.index.data(), cells.count, in.layout, slice_start.data(), level, bounds.data());
      after_launch("cell_corner_bounds");
    }
    const double corner_bound = thrust::reduce(
        thrust::device, bounds.data(), bounds.data() + cells.count, 0.0, thrust::maximum<double>());
    node_bound = std::max(node_bound, corner_bound);
  }
  const double rounding = in.rounding_for_node_bound(node_bound);

  const auto volume_count = std::uint32_t(in.volumes.size());
  const DeviceArray<gpu_ptsv::Volume> volumes = upload_and_free(in.volumes);
  const DeviceArray<geometry::ReceiverHalfSpace> half_spaces = upload_and_free(in.half_spaces);
  std::vector<DeviceArray<std::uint32_t>> live(h.levels.size());
  for (std::size_t l = 0; l < h.levels.size(); ++l) {
    live[l].resize(h.levels[l].count);
    if (h.levels[l].count != 0)
      check(cudaMemcpy(live[l].data(), h.levels[l].child_mask.data(),
                       h.levels[l].count * sizeof(std::uint32_t), cudaMemcpyDeviceToDevice),
            "cudaMemcpy");
  }
  DeviceArray<std::uint32_t> shadow_bits((std::size_t(count) + 31) / 32);
  shadow_bits.zero();
  TraversalParams params{in.layout,         slice_start.data(),
                         volumes.data(),    Tolerances{rounding, in.accept_bias},
                         in.implicit_cells, in.extra_planes};
  const SampleData data{samples.data(), half_spaces.data(), tile_offsets.data(),
                        tile_samples.data()};
  traverse(h, live, params, data, volume_count, in.job_level, shadow_bits.data(), result.counters,
           launches);

  // Results.
  result.key = keys.download();
  const std::vector<std::uint32_t> bits = shadow_bits.download();
  result.shadowed.assign(count, 0);
  for (std::uint32_t s = 0; s < count; ++s) result.shadowed[s] = (bits[s / 32] >> (s % 32)) & 1u;
  result.levels.resize(h.levels.size());
  for (std::size_t l = 0; l < h.levels.size(); ++l) {
    const DeviceLevel& d = h.levels[l];
    gpu_ptsv::Level& level = result.levels[l];
    level.index = d.index.download();
    level.child_mask = d.child_mask.download();
    const std::vector<NodeBox> boxes = d.box.download();
    for (const NodeBox& box : boxes) {
      level.lo.insert(level.lo.end(), box.lo, box.lo + 3);
      level.hi.insert(level.hi.end(), box.hi, box.hi + 3);
      level.reach.push_back(box.reach);
    }
  }
  result.threads = launches.threads;
  return result;
}

}  // namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE::ptsv
