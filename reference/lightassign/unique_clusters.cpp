#include "reference/lightassign/unique_clusters.h"

#include <algorithm>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace shadowcts {

UniqueClusters find_unique_clusters(const std::vector<std::uint32_t>& sample_tile,
                                    const std::vector<std::uint32_t>& sample_key,
                                    std::uint32_t tile_count) {
  const std::size_t n = sample_tile.size();
  // Counting sort of the samples by tile (stable: sample order within a tile).
  std::vector<std::uint32_t> tile_offsets(std::size_t(tile_count) + 1, 0);
  for (std::size_t s = 0; s < n; ++s)
    if (sample_tile[s] != UniqueClusters::no_cluster) ++tile_offsets[sample_tile[s] + 1];
  for (std::uint32_t t = 0; t < tile_count; ++t) tile_offsets[t + 1] += tile_offsets[t];
  std::vector<std::pair<std::uint32_t, std::uint32_t>> by_tile(tile_offsets.back());  // key, s
  {
    std::vector<std::uint32_t> fill(tile_offsets.begin(), tile_offsets.end() - 1);
    for (std::size_t s = 0; s < n; ++s)
      if (sample_tile[s] != UniqueClusters::no_cluster)
        by_tile[fill[sample_tile[s]]++] = {sample_key[s], std::uint32_t(s)};
  }

  // Local sort per tile and the count of distinct keys.
  std::vector<std::uint32_t> cluster_offsets(std::size_t(tile_count) + 1, 0);
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, tile_count, 16), [&](const auto& r) {
    for (std::uint32_t t = r.begin(); t != r.end(); ++t) {
      const auto first = by_tile.begin() + tile_offsets[t];
      const auto last = by_tile.begin() + tile_offsets[t + 1];
      std::sort(first, last);  // (key, sample) pairs are unique: a total order
      std::uint32_t distinct = 0;
      for (auto it = first; it != last; ++it)
        distinct += it == first || it->first != (it - 1)->first;
      cluster_offsets[t + 1] = distinct;
    }
  });
  for (std::uint32_t t = 0; t < tile_count; ++t) cluster_offsets[t + 1] += cluster_offsets[t];

  // Compaction: every cluster gets its id, key, tile and members.
  UniqueClusters out;
  const std::uint32_t clusters = cluster_offsets.back();
  out.keys.resize(clusters);
  out.tiles.resize(clusters);
  out.member_offsets.assign(std::size_t(clusters) + 1, 0);
  out.members.resize(by_tile.size());
  out.cluster_of_sample.assign(n, UniqueClusters::no_cluster);
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, tile_count, 16), [&](const auto& r) {
    for (std::uint32_t t = r.begin(); t != r.end(); ++t) {
      std::uint32_t cluster = cluster_offsets[t] - 1;
      for (std::uint32_t e = tile_offsets[t]; e < tile_offsets[t + 1]; ++e) {
        if (e == tile_offsets[t] || by_tile[e].first != by_tile[e - 1].first) {
          ++cluster;
          out.keys[cluster] = by_tile[e].first;
          out.tiles[cluster] = t;
          out.member_offsets[cluster] = e;  // members keep the by-tile order
        }
        out.members[e] = by_tile[e].second;
        out.cluster_of_sample[by_tile[e].second] = cluster;
      }
    }
  });
  out.member_offsets[clusters] = std::uint32_t(by_tile.size());
  return out;
}

}  // namespace shadowcts
