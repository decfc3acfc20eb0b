#include "simd/lightassign/unique_clusters.h"

#include <algorithm>
#include <utility>

#include <glm/vec3.hpp>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "reference/lightassign/view_frustum.h"

namespace shadowcts::simd {

UniqueClusters find_unique_clusters(const std::vector<std::uint32_t>& pixel_key,
                                    const std::vector<std::uint8_t>& clustered, std::uint32_t width,
                                    std::uint32_t height, std::uint32_t tile_size) {
  const std::uint32_t tiles_x = (width + tile_size - 1) / tile_size;
  const std::uint32_t tiles_y = (height + tile_size - 1) / tile_size;
  const std::uint32_t tile_count = tiles_x * tiles_y;
  auto for_each_pixel = [&](std::uint32_t t, auto&& f) {
    const std::uint32_t x0 = (t % tiles_x) * tile_size, y0 = (t / tiles_x) * tile_size;
    const std::uint32_t x1 = std::min(x0 + tile_size, width), y1 = std::min(y0 + tile_size, height);
    for (std::uint32_t y = y0; y < y1; ++y)
      for (std::uint32_t x = x0; x < x1; ++x) {
        const std::uint32_t s = y * width + x;
        if (clustered[s]) f(s);
      }
  };

  std::vector<std::uint32_t> tile_offsets(std::size_t(tile_count) + 1, 0);
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, tile_count, 16), [&](const auto& r) {
    for (std::uint32_t t = r.begin(); t != r.end(); ++t) {
      std::uint32_t count = 0;
      for_each_pixel(t, [&](std::uint32_t) { ++count; });
      tile_offsets[t + 1] = count;
    }
  });
  for (std::uint32_t t = 0; t < tile_count; ++t) tile_offsets[t + 1] += tile_offsets[t];

  // Per tile: its (key, sample) pairs in sample order, sorted, and the count of distinct keys.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> by_tile(tile_offsets.back());
  std::vector<std::uint32_t> cluster_offsets(std::size_t(tile_count) + 1, 0);
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, tile_count, 16), [&](const auto& r) {
    for (std::uint32_t t = r.begin(); t != r.end(); ++t) {
      std::uint32_t e = tile_offsets[t];
      std::uint32_t low = 0xFFFFFFFFu, high = 0;
      for_each_pixel(t, [&](std::uint32_t s) {
        by_tile[e++] = {pixel_key[s], s};
        low = std::min(low, pixel_key[s]);
        high = std::max(high, pixel_key[s]);
      });
      const auto first = by_tile.begin() + tile_offsets[t];
      const auto last = by_tile.begin() + tile_offsets[t + 1];
      // Sorted by (key, sample), a total order: the pairs are in sample order already, so a
      // stable counting sort by key gives the reference's std::sort order. A tile's keys differ
      // only in their slice and normal bits, usually a narrow range.
      const std::size_t count = std::size_t(last - first);
      if (count > 1 && std::uint64_t(high) - low < 4 * count + 64) {
        std::vector<std::uint32_t> starts(std::size_t(high - low) + 2, 0);
        for (auto it = first; it != last; ++it) ++starts[it->first - low + 1];
        for (std::size_t k = 1; k < starts.size(); ++k) starts[k] += starts[k - 1];
        std::vector<std::pair<std::uint32_t, std::uint32_t>> sorted(count);
        for (auto it = first; it != last; ++it) sorted[starts[it->first - low]++] = *it;
        std::copy(sorted.begin(), sorted.end(), first);
      } else {
        std::sort(first, last);
      }
      std::uint32_t distinct = 0;
      for (auto it = first; it != last; ++it)
        distinct += it == first || it->first != (it - 1)->first;
      cluster_offsets[t + 1] = distinct;
    }
  });
  for (std::uint32_t t = 0; t < tile_count; ++t) cluster_offsets[t + 1] += cluster_offsets[t];

  // Compaction, as the reference's.
  UniqueClusters out;
  const std::uint32_t clusters = cluster_offsets.back();
  out.keys.resize(clusters);
  out.tiles.resize(clusters);
  out.member_offsets.assign(std::size_t(clusters) + 1, 0);
  out.members.resize(by_tile.size());
  out.cluster_of_sample.assign(pixel_key.size(), UniqueClusters::no_cluster);
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, tile_count, 16), [&](const auto& r) {
    for (std::uint32_t t = r.begin(); t != r.end(); ++t) {
      std::uint32_t cluster = cluster_offsets[t] - 1;
      for (std::uint32_t e = tile_offsets[t]; e < tile_offsets[t + 1]; ++e) {
        if (e == tile_offsets[t] || by_tile[e].first != by_tile[e - 1].first) {
          ++cluster;
          out.keys[cluster] = by_tile[e].first;
          out.tiles[cluster] = t;
          out.member_offsets[cluster] = e;
        }
        out.members[e] = by_tile[e].second;
        out.cluster_of_sample[by_tile[e].second] = cluster;
      }
    }
  });
  out.member_offsets[clusters] = std::uint32_t(by_tile.size());
  return out;
}

std::uint32_t grow_to_contain_all(Aabb& box, const ViewSamples& samples, const std::uint32_t* first,
                                  const std::uint32_t* last) {
  if (first == last) return 0;
  glm::vec3 low = samples.samples[*first].position, high = low;
  for (const std::uint32_t* m = first + 1; m < last; ++m) {
    const glm::vec3& p = samples.samples[*m].position;
    for (int i = 0; i < 3; ++i) {
      low[i] = p[i] < low[i] ? p[i] : low[i];
      high[i] = p[i] > high[i] ? p[i] : high[i];
    }
  }
  // Inside on every axis (false for NaN): no member is outside, nothing grows.
  if (box.min.x <= low.x && box.min.y <= low.y && box.min.z <= low.z && high.x <= box.max.x &&
      high.y <= box.max.y && high.z <= box.max.z)
    return 0;
  std::uint32_t grown = 0;
  for (const std::uint32_t* m = first; m < last; ++m)
    grown += grow_to_contain(box, samples.samples[*m].position);
  return grown;
}

}  // namespace shadowcts::simd
