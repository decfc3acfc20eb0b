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

namespace {

// A band's distinct keys: open addressing from a key to its slot (the index of its entry in the
// band's slots), at most half full.
class KeySlots {
 public:
  // The slot of `key`; `added` (the next slot) when the key is new.
  std::uint32_t find_or_add(std::uint32_t key, std::uint32_t added) {
    if (2 * (std::size_t(added) + 1) > slot_.size()) grow();
    for (std::size_t at = home(key);; at = (at + 1) & (slot_.size() - 1)) {
      if (slot_[at] == empty) {
        key_[at] = key;
        slot_[at] = added;
        return added;
      }
      if (key_[at] == key) return slot_[at];
    }
  }

 private:
  static constexpr std::uint32_t empty = 0xFFFFFFFFu;
  std::size_t home(std::uint32_t key) const {
    // Fibonacci hashing: a band's keys differ in their low (slice) and middle (column) bits.
    return std::size_t((key * 0x9E3779B1u) >> (32 - bits_));
  }
  void grow() {
    std::vector<std::uint32_t> keys = std::move(key_), slots = std::move(slot_);
    ++bits_;
    key_.assign(std::size_t(1) << bits_, 0);
    slot_.assign(std::size_t(1) << bits_, empty);
    for (std::size_t e = 0; e < slots.size(); ++e)
      if (slots[e] != empty) {
        std::size_t at = home(keys[e]);
        while (slot_[at] != empty) at = (at + 1) & (slot_.size() - 1);
        key_[at] = keys[e];
        slot_[at] = slots[e];
      }
  }
  int bits_ = 7;
  std::vector<std::uint32_t> key_ = std::vector<std::uint32_t>(std::size_t(1) << 7, 0);
  std::vector<std::uint32_t> slot_ = std::vector<std::uint32_t>(std::size_t(1) << 7, empty);
};

// A distinct key of a band: its member count and the box of its members' positions.
struct KeySlot {
  std::uint32_t key = 0, count = 0;
  glm::vec3 low{0.0f}, high{0.0f};

  // Adds `members` later samples whose box is (run_low, run_high); the box keeps the first of
  // equal values (its own), as a box grown sample by sample does.
  void add_run(const glm::vec3& run_low, const glm::vec3& run_high, std::uint32_t members) {
    if (count == 0) {
      low = run_low;
      high = run_high;
    } else {
      for (int a = 0; a < 3; ++a) {
        low[a] = run_low[a] < low[a] ? run_low[a] : low[a];
        high[a] = run_high[a] > high[a] ? run_high[a] : high[a];
      }
    }
    count += members;
  }
};

}  // namespace

SampleClusters cluster_samples(const RegularSamples& regular, const ViewFrame& frame,
                               const ClusterGrid& grid, std::uint32_t width, std::uint32_t height) {
  const std::uint32_t tile_size = grid.tile_size(), tiles_x = grid.tiles_x();
  const std::uint32_t bands = grid.tiles_y();
  const std::uint32_t normal_divisions = grid.normal_divisions();
  const std::size_t m = regular.size();
  const std::vector<std::uint32_t> row_start = regular_rows(regular, width, height);
  const SliceTable slices(grid);

  // Per band: the keys row by row, their slots (slot_of_sample), each slot's count and box. A run
  // of a row's samples with one key (one tile: a key holds its tile) finds its slot once and grows
  // a box in registers, then added to its slot's; both keep the first of equal values, as
  // grow_to_contain.
  UninitializedVector<std::uint32_t> slot_of_sample(m);
  std::vector<std::vector<KeySlot>> band_slots(bands);
  std::vector<double> band_deepest(bands, 0.0);
  tbb::parallel_for(std::uint32_t(0), bands, [&](std::uint32_t band) {
    const std::uint32_t y_end = std::min(height, (band + 1) * tile_size);
    std::vector<std::uint32_t> tile_key_of_x(width), row_key(width);
    for (std::uint32_t x = 0; x < width; ++x)
      tile_key_of_x[x] = grid.pack({.i = x / tile_size, .j = band, .k = 0, .normal = 0});
    std::vector<KeySlot>& slots = band_slots[band];
    KeySlots slot_of_key;
    for (std::uint32_t y = band * tile_size; y < y_end; ++y) {
      const std::uint32_t first = row_start[y], count = row_start[y + 1] - first;
      const float* px = regular.px.data() + first;
      const float* py = regular.py.data() + first;
      const float* pz = regular.pz.data() + first;
      row_cluster_keys(frame, slices, grid.bits_normal(), tile_key_of_x.data(), y * width,
                       regular.index.data() + first, px, py, pz, count, row_key.data(),
                       band_deepest[band]);
      if (normal_divisions > 0)
        for (std::uint32_t j = 0; j < count; ++j)
          row_key[j] |= quantize_normal(regular.normal(first + j), normal_divisions);
      std::uint32_t* slot_out = slot_of_sample.data() + first;
      for (std::uint32_t j = 0; j < count;) {
        const std::uint32_t key = row_key[j];
        std::uint32_t end = j + 1;
        while (end < count && row_key[end] == key) ++end;
        const std::uint32_t slot = slot_of_key.find_or_add(key, std::uint32_t(slots.size()));
        if (slot == slots.size()) slots.push_back({.key = key});
        float low_x = px[j], low_y = py[j], low_z = pz[j];
        float high_x = low_x, high_y = low_y, high_z = low_z;
        for (std::uint32_t e = j + 1; e < end; ++e) {
          low_x = px[e] < low_x ? px[e] : low_x;
          low_y = py[e] < low_y ? py[e] : low_y;
          low_z = pz[e] < low_z ? pz[e] : low_z;
          high_x = px[e] > high_x ? px[e] : high_x;
          high_y = py[e] > high_y ? py[e] : high_y;
          high_z = pz[e] > high_z ? pz[e] : high_z;
        }
        slots[slot].add_run({low_x, low_y, low_z}, {high_x, high_y, high_z}, end - j);
        std::fill(slot_out + j, slot_out + end, slot);
        j = end;
      }
    }
  });

  SampleClusters out;
  std::vector<std::uint32_t> band_first_cluster(std::size_t(bands) + 1, 0);
  for (std::uint32_t band = 0; band < bands; ++band) {
    band_first_cluster[band + 1] =
        band_first_cluster[band] + std::uint32_t(band_slots[band].size());
    out.deepest = std::max(out.deepest, band_deepest[band]);  // exact in any order
  }
  const std::uint32_t clusters = band_first_cluster[bands];
  UniqueClusters& found = out.clusters;
  found.keys.resize(clusters);
  found.tiles.resize(clusters);
  found.member_offsets.resize(std::size_t(clusters) + 1);
  found.member_offsets[clusters] = std::uint32_t(m);
  found.cluster_of_sample.assign(std::size_t(width) * height, UniqueClusters::no_cluster);
  out.low.resize(clusters);
  out.high.resize(clusters);

  // Per band: its slots in key order are its clusters in the reference's order; the samples in
  // pixel order then take their clusters (a run of one slot keeps its cluster in a register).
  tbb::parallel_for(std::uint32_t(0), bands, [&](std::uint32_t band) {
    const std::vector<KeySlot>& slots = band_slots[band];
    std::vector<std::uint32_t> by_key(slots.size());
    for (std::uint32_t s = 0; s < by_key.size(); ++s) by_key[s] = s;
    std::sort(by_key.begin(), by_key.end(),
              [&](std::uint32_t a, std::uint32_t b) { return slots[a].key < slots[b].key; });
    std::vector<std::uint32_t> cluster_of_slot(slots.size());
    const std::uint32_t first = row_start[std::min(height, band * tile_size)];
    const std::uint32_t end = row_start[std::min(height, (band + 1) * tile_size)];
    std::uint32_t position = first;
    for (std::uint32_t rank = 0; rank < by_key.size(); ++rank) {
      const KeySlot& slot = slots[by_key[rank]];
      const std::uint32_t cluster = band_first_cluster[band] + rank;
      const ClusterCoordinates coordinates = grid.unpack(slot.key);
      cluster_of_slot[by_key[rank]] = cluster;
      found.keys[cluster] = slot.key;
      found.tiles[cluster] = coordinates.j * tiles_x + coordinates.i;
      found.member_offsets[cluster] = position;
      out.low[cluster] = slot.low;
      out.high[cluster] = slot.high;
      position += slot.count;
    }
    const std::uint32_t* const slot_of = slot_of_sample.data();
    const std::uint32_t* const pixel_of = regular.index.data();
    std::uint32_t* const cluster_of_pixel = found.cluster_of_sample.data();
    std::uint32_t run_slot = UniqueClusters::no_cluster, cluster = 0;
    for (std::uint32_t i = first; i < end; ++i) {
      if (slot_of[i] != run_slot) {
        run_slot = slot_of[i];
        cluster = cluster_of_slot[run_slot];
      }
      cluster_of_pixel[pixel_of[i]] = cluster;
    }
  });
  return out;
}

UninitializedVector<std::uint32_t> cluster_members(const UniqueClusters& clusters,
                                                   const RegularSamples& regular,
                                                   std::uint32_t width, std::uint32_t height,
                                                   std::uint32_t tile_size) {
  const std::vector<std::uint32_t> row_start = regular_rows(regular, width, height);
  // A band's samples are the members of its clusters only: each band advances its own entries.
  std::vector<std::uint32_t> next_member(clusters.member_offsets.begin(),
                                         clusters.member_offsets.end());
  UninitializedVector<std::uint32_t> members(regular.size());
  const std::uint32_t bands = (height + tile_size - 1) / tile_size;
  tbb::parallel_for(std::uint32_t(0), bands, [&](std::uint32_t band) {
    const std::uint32_t first = row_start[band * tile_size];
    const std::uint32_t end = row_start[std::min(height, (band + 1) * tile_size)];
    for (std::uint32_t i = first; i < end; ++i)
      members[next_member[clusters.cluster_of_sample[regular.index[i]]]++] = i;
  });
  return members;
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
  return grow_to_contain_all(box, low, high, regular, first, last);
}

std::uint32_t grow_to_contain_all(Aabb& box, const glm::vec3& low, const glm::vec3& high,
                                  const RegularSamples& regular, const std::uint32_t* first,
                                  const std::uint32_t* last) {
  // Inside on every axis: no member is outside, nothing grows.
  if (box_holds(box, low, high)) return 0;
  std::uint32_t grown = 0;
  for (const std::uint32_t* m = first; m < last; ++m)
    grown += grow_to_contain(box, regular.position(*m));
  return grown;
}

}  // namespace shadowcts::simd
