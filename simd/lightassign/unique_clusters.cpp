#include "simd/lightassign/unique_clusters.h"

#include <algorithm>
#include <utility>

#include <glm/vec3.hpp>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "reference/lightassign/view_frustum.h"

namespace shadowcts::simd {

std::vector<std::uint32_t> regular_rows(const RegularSamples& regular, std::uint32_t width,
                                        std::uint32_t height) {
  std::vector<std::uint32_t> start(std::size_t(height) + 1, std::uint32_t(regular.size()));
  tbb::parallel_for(std::uint32_t(0), height, [&](std::uint32_t y) {
    start[y] = std::uint32_t(
        std::lower_bound(regular.index.begin(), regular.index.end(), std::uint64_t(y) * width) -
        regular.index.begin());
  });
  return start;
}

UniqueClusters find_unique_clusters(const RegularSamples& regular, const std::uint32_t* key,
                                    std::uint32_t width, std::uint32_t height,
                                    std::uint32_t tile_size,
                                    UninitializedVector<std::uint32_t>& member_regular,
                                    bool with_members) {
  const std::uint32_t tiles_x = (width + tile_size - 1) / tile_size;
  const std::uint32_t tiles_y = (height + tile_size - 1) / tile_size;
  const std::uint32_t tile_count = tiles_x * tiles_y;
  const std::size_t m = regular.size();

  // Each pixel row's run of regular samples (a band's rows are consecutive), the tile column of
  // every x (no division per sample), and each tile's count.
  const std::vector<std::uint32_t> row_start = regular_rows(regular, width, height);
  std::vector<std::uint32_t> column_of(width);
  for (std::uint32_t x = 0; x < width; ++x) column_of[x] = x / tile_size;
  auto band_rows = [&](std::uint32_t band, auto&& f) {
    for (std::uint32_t y = band * tile_size; y < std::min(height, (band + 1) * tile_size); ++y)
      for (std::uint32_t i = row_start[y]; i < row_start[y + 1]; ++i)
        f(i, column_of[regular.index[i] - y * width]);
  };
  std::vector<std::uint32_t> tile_offsets(std::size_t(tile_count) + 1, 0);
  tbb::parallel_for(std::uint32_t(0), tiles_y, [&](std::uint32_t band) {
    std::uint32_t* count = tile_offsets.data() + std::size_t(band) * tiles_x + 1;
    band_rows(band, [&](std::uint32_t, std::uint32_t column) { ++count[column]; });
  });
  for (std::uint32_t t = 0; t < tile_count; ++t) tile_offsets[t + 1] += tile_offsets[t];

  // Per band: the samples bucketed by tile in pixel order, then each tile's stable sort by key
  // into place, and its count of distinct keys.
  // by_tile: regular indices, in the reference's by-tile (key, sample) order.
  UninitializedVector<std::uint32_t>& by_tile = member_regular;
  by_tile.resize(m);
  std::vector<std::uint32_t> cluster_offsets(std::size_t(tile_count) + 1, 0);
  // Scratch in one piece from the calling thread (a band uses its own stretch): buffers made by
  // the workers would come from their malloc arenas, fresh pages on every call.
  UninitializedVector<std::uint32_t> bucketed_all(m);
  UninitializedVector<std::uint8_t> slot_all(m);
  tbb::parallel_for(std::uint32_t(0), tiles_y, [&](std::uint32_t band) {
    const std::uint32_t first_tile = band * tiles_x, base = tile_offsets[first_tile];
    std::uint32_t* const bucketed = bucketed_all.data() + base;
    std::uint8_t* const slot_of = slot_all.data() + base;
    std::vector<std::uint32_t> fill(tile_offsets.begin() + first_tile,
                                    tile_offsets.begin() + first_tile + tiles_x);
    band_rows(band,
              [&](std::uint32_t i, std::uint32_t column) { bucketed[fill[column]++ - base] = i; });
    for (std::uint32_t t = first_tile; t < first_tile + tiles_x; ++t) {
      const std::uint32_t* first = bucketed + (tile_offsets[t] - base);
      const std::uint32_t* last = bucketed + (tile_offsets[t + 1] - base);
      std::uint32_t* out = by_tile.data() + tile_offsets[t];
      if (first == last) continue;
      const std::size_t count = std::size_t(last - first);
      // A tile holds few distinct keys (its slices and normal cells): each sample finds its key's
      // slot in a short list, most often the previous sample's; the slots in key order give each
      // key's first position, and the samples go there in pixel order (stable).
      constexpr std::uint32_t max_distinct = 64;
      std::uint32_t distinct_key[max_distinct], members[max_distinct], distinct = 0, slot = 0;
      std::uint8_t* const slot_in = slot_of + (tile_offsets[t] - base);
      std::size_t j = 0;
      for (; j < count; ++j) {
        const std::uint32_t k = key[first[j]];
        if (j == 0 || k != distinct_key[slot]) {
          slot = 0;
          while (slot < distinct && distinct_key[slot] != k) ++slot;
          if (slot == distinct) {
            if (distinct == max_distinct) break;
            distinct_key[distinct] = k;
            members[distinct++] = 0;
          }
        }
        slot_in[j] = std::uint8_t(slot);
        ++members[slot];
      }
      if (j == count) {
        std::uint32_t rank[max_distinct], start[max_distinct];
        for (std::uint32_t d = 0; d < distinct; ++d) rank[d] = d;
        std::sort(rank, rank + distinct, [&](std::uint32_t x, std::uint32_t y) {
          return distinct_key[x] < distinct_key[y];
        });
        std::uint32_t position = 0;
        for (std::uint32_t d = 0; d < distinct; ++d) {
          start[rank[d]] = position;
          position += members[rank[d]];
        }
        for (std::size_t e = 0; e < count; ++e) out[start[slot_in[e]]++] = first[e];
      } else {
        std::copy(first, last, out);
        // (key, index) pairs are unique: a total order.
        std::sort(out, out + count, [&](std::uint32_t x, std::uint32_t y) {
          return key[x] != key[y] ? key[x] < key[y] : x < y;
        });
        distinct = 1;
        for (std::size_t e = 1; e < count; ++e) distinct += key[out[e]] != key[out[e - 1]];
      }
      cluster_offsets[t + 1] = distinct;
    }
  });
  for (std::uint32_t t = 0; t < tile_count; ++t) cluster_offsets[t + 1] += cluster_offsets[t];

  // Compaction, as the reference's.
  UniqueClusters out;
  const std::uint32_t clusters = cluster_offsets.back();
  out.keys.resize(clusters);
  out.tiles.resize(clusters);
  out.member_offsets.resize(std::size_t(clusters) + 1);
  if (with_members) out.members.resize(m);
  out.cluster_of_sample.assign(std::size_t(width) * height, UniqueClusters::no_cluster);
  tbb::parallel_for(std::uint32_t(0), tiles_y, [&](std::uint32_t band) {
    for (std::uint32_t t = band * tiles_x; t < (band + 1) * tiles_x; ++t) {
      std::uint32_t cluster = cluster_offsets[t] - 1, previous = 0;
      for (std::uint32_t e = tile_offsets[t]; e < tile_offsets[t + 1]; ++e) {
        const std::uint32_t i = by_tile[e], k = key[i];
        if (e == tile_offsets[t] || k != previous) {
          ++cluster;
          out.keys[cluster] = k;
          out.tiles[cluster] = t;
          out.member_offsets[cluster] = e;
          previous = k;
        }
        const std::uint32_t s = regular.index[i];
        if (with_members) out.members[e] = s;
        out.cluster_of_sample[s] = cluster;
      }
    }
  });
  out.member_offsets[clusters] = std::uint32_t(m);
  return out;
}

std::uint32_t grow_to_contain_all(Aabb& box, const RegularSamples& regular,
                                  const std::uint32_t* first, const std::uint32_t* last) {
  if (first == last) return 0;
  glm::vec3 low = regular.position(*first), high = low;
  for (const std::uint32_t* m = first + 1; m < last; ++m) {
    const float p[3] = {regular.px[*m], regular.py[*m], regular.pz[*m]};
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
    grown += grow_to_contain(box, regular.position(*m));
  return grown;
}

}  // namespace shadowcts::simd
