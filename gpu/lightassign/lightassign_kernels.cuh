#pragma once
// The lightassign pipeline, written once (gpu/emulator/kernel.h): nvcc builds it into the `cuda`
// backend, the host compiler into `cuda-emu` against the emulator. Device-wide steps (sort,
// unique, scan, reduce, lower bound) go through Thrust; the host only reads back sizes, decides
// the rare doubtful depth slices and supplies the slice planes (glibc's log and pow define them in
// the reference; the device's differ by ulps).
#include <chrono>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include <thrust/binary_search.h>
#include <thrust/count.h>
#include <thrust/execution_policy.h>
#include <thrust/functional.h>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/reduce.h>
#include <thrust/scan.h>
#include <thrust/sort.h>

#include "gpu/emulator/kernel.h"
#include "gpu/lightassign/cluster_key.cuh"
#include "gpu/lightassign/clustered_assignment.cuh"
#include "gpu/lightassign/device_buffer.cuh"
#include "gpu/lightassign/light_bvh.cuh"
#include "gpu/lightassign/lightassign_kernels.h"
#include "gpu/lightassign/tiled_assignment.cuh"
#include "gpu/lightassign/unique_clusters.cuh"

namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE::lightassign {

// counts[0 .. lists) -> exclusive offsets[0 .. lists]; returns the total.
inline unsigned long long scan_counts(DeviceArray<unsigned long long>& counts, std::size_t lists) {
  // counts has lists + 1 entries, the last 0: its offset is the total.
  check(cudaMemset(counts.data() + lists, 0, sizeof(unsigned long long)), "cudaMemset");
  thrust::exclusive_scan(thrust::device, counts.data(), counts.data() + lists + 1, counts.data());
  return counts.at(lists);
}

inline std::vector<std::uint32_t> list_offsets(const DeviceArray<unsigned long long>& offsets,
                                               std::size_t lists) {
  const std::vector<unsigned long long> wide = offsets.download(lists + 1);
  if (wide.back() > 0xFFFFFFFFull)
    throw std::length_error("light lists: more than 2^32 - 1 entries in all");
  return std::vector<std::uint32_t>(wide.begin(), wide.end());
}

// Takes the input by value: each host array is freed once uploaded.
inline LightAssignKernelResult run(LightAssignKernelInput in) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  LightAssignKernelResult result;
  Launches launches;
  if (in.sample_pixel.size() >= 0xFFFFFFFFull || in.lights.size() >= 0xFFFFFFFFull)
    throw std::length_error("lightassign: 2^32 - 1 or more samples or lights");
  const auto n = std::uint32_t(in.sample_pixel.size());
  const auto light_count = std::uint32_t(in.lights.size());
  const LightAssignFrame& frame = in.frame;
  const DeviceArray<std::uint32_t> pixel = upload_and_free(in.sample_pixel);
  const DeviceArray<glm::vec3> position = upload_and_free(in.sample_position);
  const DeviceArray<glm::vec3> normal = upload_and_free(in.sample_normal);
  const DeviceArray<LightAssignSphere> spheres = upload_and_free(in.lights);

  // View depths (Section 3.1); the slices reach the deepest sample.
  DeviceArray<double> depth(n);
  if (n > 0) {
    SHADOWCTS_LAUNCH(sample_depths, launches.blocks_for(n, threads_per_block), threads_per_block, 0)
    (n, position.data(), frame, depth.data());
    Launches::finish("sample_depths");
  }
  LightAssignGrid grid;
  DeviceArray<std::uint32_t> slice;
  if (in.tiled) {
    grid.tiles_x = (frame.width + in.tile_size - 1) / in.tile_size;
    grid.tiles_y = (frame.height + in.tile_size - 1) / in.tile_size;
  } else {
    const double deepest = n == 0 ? 0.0
                                  : thrust::reduce(thrust::device, depth.data(), depth.data() + n,
                                                   0.0, thrust::maximum<double>());
    grid = in.hooks.grid(deepest);
    result.key_bits = std::uint64_t(grid.bits);
    slice.resize(n);
    DeviceArray<std::uint8_t> doubtful(n);
    if (n > 0) {
      SHADOWCTS_LAUNCH(sample_slices, launches.blocks_for(n, threads_per_block), threads_per_block,
                       0)
      (n, depth.data(), grid, slice.data(), doubtful.data());
      Launches::finish("sample_slices");
      const auto doubts =
          thrust::count(thrust::device, doubtful.data(), doubtful.data() + n, std::uint8_t(1));
      if (doubts > 0) {
        std::vector<std::uint32_t> host_slice = slice.download();
        const std::vector<double> host_depth = depth.download();
        const std::vector<std::uint8_t> host_doubt = doubtful.download();
        for (std::uint32_t i = 0; i < n; ++i)
          if (host_doubt[i]) host_slice[i] = in.hooks.slice_of(host_depth[i]);
        slice.upload(host_slice);
      }
    }
  }

  // Keys, then the unique clusters (tiles for the tiled variant) by sort + unique.
  DeviceArray<std::uint32_t> key(n);
  DeviceArray<std::uint64_t> sort_key(n);
  if (n > 0) {
    SHADOWCTS_LAUNCH(sample_keys, launches.blocks_for(n, threads_per_block), threads_per_block, 0)
    (n, pixel.data(), slice.data(), normal.data(), grid, frame.width, in.tile_size,
     in.tiled ? 0u : in.normal_divisions, in.tiled, key.data(), sort_key.data());
    Launches::finish("sample_keys");
  }
  result.sample_key = key.download();
  DeviceClusters clusters;
  find_unique_clusters(n, sort_key, clusters, launches);
  const std::uint32_t lists = clusters.count;

  DeviceArray<LightAssignBox> bounds(lists);
  DeviceArray<std::uint32_t> grown(lists);
  DeviceArray<unsigned long long> counts(std::size_t(lists) + 1);
  DeviceArray<std::uint32_t> out_lights;
  std::vector<std::uint32_t> offsets{0};
  const auto warp_blocks = [&](std::uint32_t warps) {
    return launches.blocks_for(std::size_t(warps) * lanes_per_warp, threads_per_block);
  };
  if (!in.tiled) {
    // The slice planes of each cluster's sub-frustum, from the reference's slice_near.
    std::vector<double> near_host, far_host;
    if (!in.explicit_bounds) {
      const std::vector<std::uint32_t> keys = clusters.keys.download();
      near_host.resize(lists);
      far_host.resize(lists);
      const std::uint32_t k_mask = grid.bits_k == 0 ? 0u : (1u << grid.bits_k) - 1u;
      for (std::uint32_t c = 0; c < lists; ++c) {
        const std::uint32_t k =
            grid.bits_normal >= 32 ? 0u : (keys[c] >> grid.bits_normal) & k_mask;
        near_host[c] = in.hooks.slice_near(k);
        far_host[c] = in.hooks.slice_near(std::uint64_t(k) + 1);
      }
    }
    DeviceArray<double> slice_near, slice_far;
    slice_near.upload(near_host);
    slice_far.upload(far_host);
    DeviceArray<NormalCone> cones(lists);
    ClusterSettings settings;
    settings.tile_size = in.tile_size;
    settings.tiles_x = grid.tiles_x;
    settings.normal_divisions = in.normal_divisions;
    settings.bits_k = grid.bits_k;
    settings.bits_normal = grid.bits_normal;
    settings.explicit_bounds = in.explicit_bounds;
    settings.explicit_normal_cones = in.explicit_normal_cones;
    if (lists > 0) {
      SHADOWCTS_LAUNCH(cluster_bounds, launches.blocks_for(lists, threads_per_block),
                       threads_per_block, 0)
      (lists, clusters.keys.data(), clusters.tiles.data(), clusters.member_offsets.data(),
       clusters.members.data(), position.data(), normal.data(), slice_near.data(), slice_far.data(),
       frame, settings, bounds.data(), cones.data(), grown.data());
      Launches::finish("cluster_bounds");
    }
    const DeviceLightBvh bvh(spheres, launches);
    result.light_order = bvh.order().download();
    result.build_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();

    const bool use_cones = in.explicit_normal_cones || in.normal_divisions > 0;
    DeviceArray<WorkCounters> work(1);
    work.fill_bytes(0);
    KernelProgress progress;
    if (lists > 0) {
      const unsigned blocks = warp_blocks(lists);
      SHADOWCTS_LAUNCH(cluster_lights, blocks, threads_per_block, 0)
      (lists, bounds.data(), cones.data(), use_cones, bvh.view(), spheres.data(), counts.data(),
       work.data(), nullptr, nullptr, progress.counter());
      progress.wait("cluster_lights (count)", blocks);
    }
    const unsigned long long total = scan_counts(counts, lists);
    offsets = list_offsets(counts, lists);
    out_lights.resize(total);
    if (lists > 0 && total > 0) {
      const unsigned blocks = warp_blocks(lists);
      SHADOWCTS_LAUNCH(cluster_lights, blocks, threads_per_block, 0)
      (lists, bounds.data(), cones.data(), use_cones, bvh.view(), spheres.data(), nullptr, nullptr,
       counts.data(), out_lights.data(), progress.counter());
      progress.wait("cluster_lights (write)", blocks);
    }
    const WorkCounters w = work.at(0);
    result.nodes_tested = w.nodes_tested;
    result.light_tests = w.light_tests;
    result.backface_culled = w.backface_culled;
  } else {
    const std::uint32_t tile_count = grid.tiles_x * grid.tiles_y;
    DeviceArray<std::uint32_t> list_of_tile(tile_count);
    list_of_tile.fill_bytes(0xFF);
    DeviceArray<SubFrustum> sub_frusta(lists);
    if (lists > 0) {
      launches.threads += std::uint64_t(lists) * threads_per_block;
      SHADOWCTS_LAUNCH(tile_volumes, lists, threads_per_block, 0)
      (lists, clusters.tiles.data(), clusters.member_offsets.data(), clusters.members.data(),
       depth.data(), position.data(), frame, in.tile_size, grid.tiles_x, sub_frusta.data(),
       bounds.data(), grown.data(), list_of_tile.data());
      Launches::finish("tile_volumes");
    }
    result.build_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();

    // Candidates: (list, light) pairs in light order, grouped by list.
    DeviceArray<TileRect> rects(light_count);
    DeviceArray<unsigned long long> pair_offset(std::size_t(light_count) + 1);
    if (light_count > 0) {
      SHADOWCTS_LAUNCH(light_rects, launches.blocks_for(light_count, threads_per_block),
                       threads_per_block, 0)
      (light_count, spheres.data(), frame, in.tile_size, grid.tiles_x, grid.tiles_y,
       list_of_tile.data(), rects.data(), pair_offset.data());
      Launches::finish("light_rects");
    }
    const unsigned long long pairs = scan_counts(pair_offset, light_count);
    DeviceArray<std::uint32_t> pair_list(pairs), pair_light(pairs);
    if (pairs > 0) {
      SHADOWCTS_LAUNCH(light_pairs, launches.blocks_for(light_count, threads_per_block),
                       threads_per_block, 0)
      (light_count, rects.data(), grid.tiles_x, list_of_tile.data(), pair_offset.data(),
       pair_list.data(), pair_light.data());
      Launches::finish("light_pairs");
      thrust::stable_sort_by_key(thrust::device, pair_list.data(), pair_list.data() + pairs,
                                 pair_light.data());
    }
    DeviceArray<unsigned long long> candidate_offset(std::size_t(lists) + 1);
    thrust::lower_bound(thrust::device, pair_list.data(), pair_list.data() + pairs,
                        thrust::counting_iterator<std::uint32_t>(0),
                        thrust::counting_iterator<std::uint32_t>(lists + 1),
                        candidate_offset.data());
    result.light_tests = pairs;
    if (lists > 0) {
      SHADOWCTS_LAUNCH(tile_lights, warp_blocks(lists), threads_per_block, 0)
      (lists, candidate_offset.data(), pair_light.data(), sub_frusta.data(), bounds.data(),
       spheres.data(), frame, counts.data(), nullptr, nullptr);
      Launches::finish("tile_lights (count)");
    }
    const unsigned long long total = scan_counts(counts, lists);
    offsets = list_offsets(counts, lists);
    out_lights.resize(total);
    if (lists > 0 && total > 0) {
      SHADOWCTS_LAUNCH(tile_lights, warp_blocks(lists), threads_per_block, 0)
      (lists, candidate_offset.data(), pair_light.data(), sub_frusta.data(), bounds.data(),
       spheres.data(), frame, nullptr, counts.data(), out_lights.data());
      Launches::finish("tile_lights (write)");
    }
  }

  result.offsets = std::move(offsets);
  result.lights = out_lights.download();
  result.bounds = bounds.download();
  for (const std::uint32_t g : grown.download()) result.bounds_grown += g;
  result.cluster_keys = clusters.keys.download();
  result.cluster_tiles = clusters.tiles.download();
  result.member_offsets = clusters.member_offsets.download(std::size_t(lists) + 1);
  result.members = clusters.members.download();
  result.list_of_regular = clusters.cluster_of_sample.download();
  result.emulated_threads = launches.threads;
  result.query_ms =
      std::chrono::duration<double, std::milli>(Clock::now() - start).count() - result.build_ms;
  return result;
}

}  // namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE::lightassign
