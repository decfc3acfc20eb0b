#pragma once
// Finding the unique clusters by sorting and compaction (Paper II, Section 3.2, "local sorting";
// Section 4.2): the samples of each screen tile are sorted by key locally, runs of equal keys are
// compacted into clusters, and a prefix sum over the tiles' cluster counts gives every cluster
// its global id. Cluster ids therefore follow tile order, then key order.
#include <cstdint>
#include <vector>

namespace shadowcts {

struct UniqueClusters {
  std::vector<std::uint32_t> keys;               // per cluster
  std::vector<std::uint32_t> tiles;              // per cluster: its screen tile
  std::vector<std::uint32_t> member_offsets;     // per cluster + 1, into members
  std::vector<std::uint32_t> members;            // sample indices, grouped by cluster, ascending
  std::vector<std::uint32_t> cluster_of_sample;  // per sample; no_cluster if it has none
  static constexpr std::uint32_t no_cluster = 0xFFFFFFFFu;
};

// sample_tile[s]: the tile of sample s, or no_cluster for samples that are not clustered;
// sample_key[s]: its cluster key (read only when it has a tile).
UniqueClusters find_unique_clusters(const std::vector<std::uint32_t>& sample_tile,
                                    const std::vector<std::uint32_t>& sample_key,
                                    std::uint32_t tile_count);

}  // namespace shadowcts
