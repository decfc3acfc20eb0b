#include "simd/ptsv/hierarchy.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <functional>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "shadowcts/distinct_key_sort.h"

namespace shadowcts::simd::ptsv {
namespace {

// A coordinate extreme and the smallest sample index that reaches it (see hierarchy.h).
struct Extreme {
  double value;
  std::uint32_t sample;
};

// b replaces a when smaller, or equal (a signed zero) from an earlier sample.
inline void take_min(Extreme& a, const Extreme& b) {
  if (b.value < a.value || (!(a.value < b.value) && b.sample < a.sample)) a = b;
}
inline void take_max(Extreme& a, const Extreme& b) {
  if (a.value < b.value || (!(b.value < a.value) && b.sample < a.sample)) a = b;
}

struct NodeExtremes {
  std::array<Extreme, 3> lo, hi;
  double reach;
};

NodeExtremes empty_extremes() {
  constexpr double inf = std::numeric_limits<double>::infinity();
  constexpr std::uint32_t none = 0xFFFFFFFFu;
  NodeExtremes e;
  for (int k = 0; k < 3; ++k) {
    e.lo[std::size_t(k)] = {inf, none};
    e.hi[std::size_t(k)] = {-inf, none};
  }
  e.reach = 0.0;
  return e;
}

void store(Level& level, std::size_t at, const NodeExtremes& e) {
  for (std::size_t k = 0; k < 3; ++k) {
    level.lo[k][at] = e.lo[k].value;
    level.hi[k][at] = e.hi[k].value;
  }
  level.reach[at] = e.reach;
}

void allocate(Level& level) {
  const std::size_t n = level.size() + lane_padding;
  for (std::size_t k = 0; k < 3; ++k) {
    level.lo[k].assign(n, 0.0);
    level.hi[k].assign(n, 0.0);
  }
  level.reach.assign(n, 0.0);
  level.child_mask.assign(level.size(), 0u);
  level.first_child.assign(level.size(), 0u);
  level.parent.assign(level.size(), 0u);
}

// Ascending (sort_distinct_keys: the pairs are distinct). At gate_house.1M the build phase went
// from 30 to 20 ms with it, of which tbb::parallel_sort had taken 10-11 ms.
void sort_keys(std::vector<std::uint64_t>& keys) {
  std::vector<std::uint64_t> sorted(keys.size());
  sort_distinct_keys(keys.data(), keys.size(), sorted.data(), std::less<std::uint64_t>());
  keys.swap(sorted);
}

}  // namespace

std::uint64_t Hierarchy::node_count() const {
  std::uint64_t n = 0;
  for (const Level& level : levels) n += level.size();
  return n;
}

Hierarchy build_hierarchy(const ref::ClusterKeyLayout& layout, const ref::ViewFrame& frame,
                          const PreparedScene& scene, const std::vector<std::uint32_t>& key,
                          const std::vector<double>& reach, bool implicit_cells) {
  Hierarchy h;
  h.layout = layout;
  const int leaves = h.leaf_level();
  h.levels.resize(std::size_t(leaves) + 1);
  const std::size_t n = key.size();
  const RegularSamples& samples = scene.samples;

  // (key, sample) pairs sorted: each leaf's samples are one run, in sample order.
  std::vector<std::uint64_t> pairs(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 8192),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i != r.end(); ++i)
                        pairs[i] = (std::uint64_t(key[i]) << 32) | std::uint64_t(i);
                    });
  sort_keys(pairs);

  Level& leaf = h.levels[std::size_t(leaves)];
  std::vector<std::uint32_t> run_start;
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t k = std::uint32_t(pairs[i] >> 32);
    if (leaf.index.empty() || leaf.index.back() != k) {
      leaf.index.push_back(k);
      run_start.push_back(std::uint32_t(i));
    }
  }
  run_start.push_back(std::uint32_t(n));
  allocate(leaf);
  h.leaf_of_sample.assign(n, 0u);
  std::vector<NodeExtremes> extremes(leaf.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leaf.size(), 64), [&](const tbb::
                                                                                 blocked_range<
                                                                                     std::size_t>&
                                                                                     r) {
    for (std::size_t l = r.begin(); l != r.end(); ++l) {
      // The reference's fold, in sample order: glm::min / glm::max and std::max.
      NodeExtremes e = empty_extremes();
      for (std::uint32_t j = run_start[l]; j < run_start[l + 1]; ++j) {
        const std::uint32_t s = std::uint32_t(pairs[j]);
        h.leaf_of_sample[s] = std::uint32_t(l);
        const double p[3] = {double(samples.px[s]), double(samples.py[s]), double(samples.pz[s])};
        for (std::size_t k = 0; k < 3; ++k) {
          if (p[k] < e.lo[k].value) e.lo[k] = {p[k], s};
          if (e.hi[k].value < p[k]) e.hi[k] = {p[k], s};
        }
        if (e.reach < reach[s]) e.reach = reach[s];
      }
      store(leaf, l, e);
      extremes[l] = e;
    }
  });

  // Upper levels: the distinct prefixes of the level below, children contiguous.
  for (int l = leaves - 1; l >= 0; --l) {
    Level& below = h.levels[std::size_t(l) + 1];
    Level& level = h.levels[std::size_t(l)];
    std::vector<std::uint32_t> first;
    for (std::size_t c = 0; c < below.size(); ++c) {
      const std::uint32_t index = below.index[c] >> ref::fanout_bits;
      if (level.index.empty() || level.index.back() != index) {
        level.index.push_back(index);
        first.push_back(std::uint32_t(c));
      }
    }
    if (l == 0 && level.index.empty()) level.index.push_back(0);  // the root always exists
    first.push_back(std::uint32_t(below.size()));
    allocate(level);
    std::vector<NodeExtremes> next(level.size(), empty_extremes());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, level.size(), 64),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t p = r.begin(); p != r.end(); ++p) {
                          if (p + 1 >= first.size()) {  // the root without samples
                            store(level, p, empty_extremes());
                            continue;
                          }
                          level.first_child[p] = first[p];
                          NodeExtremes e = empty_extremes();
                          std::uint32_t mask = 0;
                          for (std::uint32_t c = first[p]; c < first[p + 1]; ++c) {
                            below.parent[c] = std::uint32_t(p);
                            mask |= 1u << (below.index[c] & 31u);
                            for (std::size_t k = 0; k < 3; ++k) {
                              take_min(e.lo[k], extremes[c].lo[k]);
                              take_max(e.hi[k], extremes[c].hi[k]);
                            }
                            if (e.reach < extremes[c].reach) e.reach = extremes[c].reach;
                          }
                          level.child_mask[p] = mask;
                          store(level, p, e);
                          next[p] = e;
                        }
                      });
    extremes.swap(next);
  }

  if (implicit_cells)
    for (int l = 1; l <= leaves; ++l) {
      Level& level = h.levels[std::size_t(l)];
      for (auto& v : level.corner) v.assign(level.size() + lane_padding, 0.0);
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, level.size(), 256),
                        [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t p = r.begin(); p != r.end(); ++p) {
                            const auto corners = ref::cell_corners(
                                frame, ref::implicit_node_cell(layout, l, level.index[p]));
                            for (std::size_t c = 0; c < 8; ++c)
                              for (std::size_t k = 0; k < 3; ++k)
                                level.corner[c * 3 + k][p] = corners[c][int(k)];
                          }
                        });
    }

  // Leaves' tiles, and the samples of each tile in sample order (a counting sort).
  h.leaf_tile.resize(leaf.size());
  for (std::size_t l = 0; l < leaf.size(); ++l) {
    const ref::ClusterCoordinate c = layout.deinterleave(leaf.index[l]);
    h.leaf_tile[l] = c.y * layout.tiles_x + c.x;
  }
  // A stable counting sort of the samples by tile, in fixed chunks spread over oneTBB: chunk c's
  // samples of tile t go after those of the chunks before it, so the order is sample order.
  const std::size_t tiles = std::size_t(layout.tiles_x) * layout.tiles_y;
  std::vector<std::uint32_t> tile_of(n);
  const std::uint32_t width = scene.view_samples.width;
  constexpr std::size_t chunks = 16;
  const std::size_t per_chunk = (n + chunks - 1) / chunks;
  std::vector<std::uint32_t> count(chunks * tiles, 0u);
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, chunks, 1), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t c = r.begin(); c != r.end(); ++c) {
          std::uint32_t* counts = count.data() + c * tiles;
          for (std::size_t i = c * per_chunk; i < std::min(n, (c + 1) * per_chunk); ++i) {
            // The pixel is the sample's place in the row-major image.
            const std::uint32_t pixel_x = samples.index[i] % width,
                                pixel_y = samples.index[i] / width;
            tile_of[i] = (pixel_y / ref::cluster_tile_size) * layout.tiles_x +
                         pixel_x / ref::cluster_tile_size;
            ++counts[tile_of[i]];
          }
        }
      });
  h.tile_offsets.assign(tiles + 1, 0u);
  for (std::size_t t = 0; t < tiles; ++t) {
    std::uint32_t at = h.tile_offsets[t];
    for (std::size_t c = 0; c < chunks; ++c) {
      const std::uint32_t k = count[c * tiles + t];
      count[c * tiles + t] = at;  // chunk c's first slot in tile t
      at += k;
    }
    h.tile_offsets[t + 1] = at;
  }
  h.tile_sample.resize(n);
  for (auto& v : h.tile_pos) v.assign(n + lane_padding, 0.0);
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, chunks, 1), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t c = r.begin(); c != r.end(); ++c) {
          std::uint32_t* fill = count.data() + c * tiles;
          for (std::size_t i = c * per_chunk; i < std::min(n, (c + 1) * per_chunk); ++i) {
            const std::uint32_t at = fill[tile_of[i]]++;
            h.tile_sample[at] = std::uint32_t(i);
            h.tile_pos[0][at] = double(samples.px[i]);
            h.tile_pos[1][at] = double(samples.py[i]);
            h.tile_pos[2][at] = double(samples.pz[i]);
          }
        }
      });
  return h;
}

}  // namespace shadowcts::simd::ptsv
