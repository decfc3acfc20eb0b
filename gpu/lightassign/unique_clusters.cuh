#pragma once
// The occupied clusters (Paper II, Sections 3.2, 4.2) on the device: the regular samples sorted
// by (tile << 32) | key with a stable Thrust sort (equal keys keep ascending sample order), the
// runs of equal sort keys made unique with their first positions (the members' offsets), and
// every member told its cluster. Cluster ids follow tile order, then key order, members ascend:
// reference/lightassign/unique_clusters.h's numbering.
#include <cstdint>

#include <thrust/execution_policy.h>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/sequence.h>
#include <thrust/sort.h>
#include <thrust/unique.h>

#include "gpu/emulator/kernel.h"
#include "gpu/lightassign/device_buffer.cuh"

namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE::lightassign {

// One thread per cluster: its key and tile, and the cluster of each of its members.
__global__ void cluster_members(std::uint32_t clusters, const std::uint64_t* unique_sort_key,
                                const std::uint32_t* member_offsets, const std::uint32_t* members,
                                std::uint32_t* cluster_key, std::uint32_t* cluster_tile,
                                std::uint32_t* cluster_of_sample) {
  const std::uint32_t c = blockIdx.x * blockDim.x + threadIdx.x;
  if (c >= clusters) return;
  cluster_key[c] = std::uint32_t(unique_sort_key[c]);
  cluster_tile[c] = std::uint32_t(unique_sort_key[c] >> 32);
  for (std::uint32_t e = member_offsets[c]; e < member_offsets[c + 1]; ++e)
    cluster_of_sample[members[e]] = c;
}

struct DeviceClusters {
  std::uint32_t count = 0;
  DeviceArray<std::uint32_t> keys, tiles, member_offsets, members, cluster_of_sample;
};

// sort_key: per regular sample (reordered here).
inline void find_unique_clusters(std::uint32_t n, DeviceArray<std::uint64_t>& sort_key,
                                 DeviceClusters& out, Launches& launches) {
  out.members.resize(n);
  thrust::sequence(thrust::device, out.members.data(), out.members.data() + n, 0u);
  thrust::stable_sort_by_key(thrust::device, sort_key.data(), sort_key.data() + n,
                             out.members.data());
  DeviceArray<std::uint64_t> unique_keys(n);
  out.member_offsets.resize(std::size_t(n) + 1);
  const auto ends = thrust::unique_by_key_copy(thrust::device, sort_key.data(), sort_key.data() + n,
                                               thrust::counting_iterator<std::uint32_t>(0),
                                               unique_keys.data(), out.member_offsets.data());
  out.count = std::uint32_t(ends.first - unique_keys.data());
  check(cudaMemcpy(out.member_offsets.data() + out.count, &n, sizeof(std::uint32_t),
                   cudaMemcpyHostToDevice),
        "cudaMemcpy to device");
  out.keys.resize(out.count);
  out.tiles.resize(out.count);
  out.cluster_of_sample.resize(n);
  if (out.count == 0) return;
  SHADOWCTS_LAUNCH(cluster_members, launches.blocks_for(out.count, threads_per_block),
                   threads_per_block, 0)
  (out.count, unique_keys.data(), out.member_offsets.data(), out.members.data(), out.keys.data(),
   out.tiles.data(), out.cluster_of_sample.data());
  Launches::finish("cluster_members");
}

}  // namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE::lightassign
