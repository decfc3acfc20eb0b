#include "oracles/caster_bvh.h"

#include <algorithm>
#include <array>
#include <utility>

#include <hwy/contrib/sort/vqsort.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "oracles/exact_segment_triangle.h"
#include "oracles/ordered_float_bits.h"
#include "shadowcts/hard_shadow_inputs.h"

namespace shadowcts {
namespace {

constexpr std::size_t max_leaf_size = 4;
constexpr std::size_t parallel_build_threshold = 4096;

// (leaves(m), leaves(m + 1)) of a median-split tree: leaves(m) = 1 for m <= max_leaf_size, else
// leaves(floor(m / 2)) + leaves(ceil(m / 2)). The pair recursion needs only log m steps, which
// lets every subtree know where its right sibling starts before either is built.
std::pair<std::size_t, std::size_t> leaf_counts(std::size_t m) {
  if (m + 1 <= max_leaf_size) return {1, 1};
  if (m <= max_leaf_size) return {1, 2};  // m == max_leaf_size; m + 1 splits into two leaves
  const auto [half, half_plus_one] = leaf_counts(m / 2);
  if (m % 2 == 0) return {2 * half, half + half_plus_one};
  return {half + half_plus_one, 2 * half_plus_one};
}

std::size_t node_count(std::size_t m) {
  return 2 * leaf_counts(m).first - 1;
}

}  // namespace

// Item ids in the order of each axis, the arrays the halves' orders are written to, and a flag
// per item.
struct CasterBvh::SortedItems {
  std::uint32_t* by_axis[3];
  std::uint32_t* spare[3];
  std::uint8_t* goes_left;
};

struct CasterBvh::BuildItem {
  float lo[3], hi[3];
  float centroid[3];
  std::uint32_t triangle;
};

CasterBvh::CasterBvh(const Case& c) {
  // The casting triangles' items in index order, compacted in pieces fixed by the input alone.
  const std::size_t n = c.triangles.size();
  constexpr std::size_t piece = std::size_t(1) << 14;
  const std::size_t pieces = (n + piece - 1) / piece;
  std::vector<std::uint8_t> casts(n, 0);
  std::vector<std::size_t> first_item(pieces + 1, 0);
  tbb::parallel_for(std::size_t(0), pieces, [&](std::size_t p) {
    std::size_t count = 0;
    for (std::size_t i = p * piece; i < std::min(n, (p + 1) * piece); ++i) {
      casts[i] = oracle_casts_shadow(c, i) ? 1 : 0;
      count += casts[i];
    }
    first_item[p + 1] = count;
  });
  for (std::size_t p = 0; p < pieces; ++p) first_item[p + 1] += first_item[p];
  std::vector<BuildItem> items(first_item[pieces]);
  tbb::parallel_for(std::size_t(0), pieces, [&](std::size_t p) {
    std::size_t next = first_item[p];
    for (std::size_t i = p * piece; i < std::min(n, (p + 1) * piece); ++i) {
      if (!casts[i]) continue;
      const Triangle& t = c.triangles[i];
      BuildItem& item = items[next++];
      for (int k = 0; k < 3; ++k) {
        item.lo[k] = std::min({t.v0[k], t.v1[k], t.v2[k]});
        item.hi[k] = std::max({t.v0[k], t.v1[k], t.v2[k]});
        item.centroid[k] = 0.5f * item.lo[k] + 0.5f * item.hi[k];
      }
      item.triangle = std::uint32_t(i);
    }
  });
  if (items.empty()) return;
  // The items in the order of their centroids along each axis, ties by index (the triangle
  // order): every median split takes the lower half of its longest axis's order and carries the
  // other two orders into the halves by stable partitions, one pass each, instead of a selection
  // over the items per node. The same splits as a selection by (centroid, triangle) would make.
  const std::size_t m = items.size();
  std::array<std::vector<std::uint32_t>, 3> order, spare;
  tbb::parallel_for(0, 3, [&](int k) {
    std::vector<std::uint64_t> keys(m);
    for (std::size_t i = 0; i < m; ++i)
      keys[i] = std::uint64_t(ordered_float_bits(items[i].centroid[k])) << 32 | i;
    hwy::Sorter()(keys.data(), m, hwy::SortAscending());
    order[std::size_t(k)].resize(m);
    spare[std::size_t(k)].resize(m);
    for (std::size_t i = 0; i < m; ++i) order[std::size_t(k)][i] = std::uint32_t(keys[i]);
  });
  std::vector<std::uint8_t> goes_left(m);
  SortedItems sorted{{order[0].data(), order[1].data(), order[2].data()},
                     {spare[0].data(), spare[1].data(), spare[2].data()},
                     goes_left.data()};
  nodes_.resize(node_count(m));
  triangles_.resize(m);
  leaf_boxes_.resize(m);
  build(items, sorted, 0, m, 0);
}

void CasterBvh::build(const std::vector<BuildItem>& items, const SortedItems& sorted,
                      std::size_t begin, std::size_t end, std::size_t node_index) {
  Node& node = nodes_[node_index];
  const std::size_t count = end - begin;
  if (count <= max_leaf_size) {
    const std::uint32_t* ids = sorted.by_axis[0];
    for (int k = 0; k < 3; ++k) {
      node.lo[k] = items[ids[begin]].lo[k];
      node.hi[k] = items[ids[begin]].hi[k];
    }
    node.first_or_right = std::uint32_t(begin);
    node.count = std::uint32_t(count);
    for (std::size_t i = begin; i < end; ++i) {
      const BuildItem& item = items[ids[i]];
      for (int k = 0; k < 3; ++k) {
        node.lo[k] = std::min(node.lo[k], item.lo[k]);
        node.hi[k] = std::max(node.hi[k], item.hi[k]);
      }
      triangles_[i] = item.triangle;
      Node& box = leaf_boxes_[i];
      std::copy(item.lo, item.lo + 3, box.lo);
      std::copy(item.hi, item.hi + 3, box.hi);
      box.first_or_right = 0;
      box.count = 1;
    }
    return;
  }
  // The longest extent of the centroids, whose ends are the ends of each axis's order.
  int axis = 0;
  float extent[3];
  for (int k = 0; k < 3; ++k)
    extent[k] =
        items[sorted.by_axis[k][end - 1]].centroid[k] - items[sorted.by_axis[k][begin]].centroid[k];
  for (int k = 1; k < 3; ++k)
    if (extent[k] > extent[axis]) axis = k;
  const std::size_t middle = begin + count / 2;
  const std::uint32_t* split = sorted.by_axis[axis];
  for (std::size_t i = begin; i < end; ++i) sorted.goes_left[split[i]] = i < middle ? 1 : 0;
  // The split axis's order is already split. The other two go to their spare arrays (same
  // places), which become the children's.
  SortedItems halves = sorted;
  for (int k = 0; k < 3; ++k) {
    if (k == axis) continue;
    std::swap(halves.by_axis[k], halves.spare[k]);
    const std::uint32_t* from = sorted.by_axis[k];
    std::uint32_t* to = halves.by_axis[k];
    std::size_t left = begin, right = middle;
    for (std::size_t i = begin; i < end; ++i) {
      const std::uint32_t id = from[i];
      to[sorted.goes_left[id] ? left++ : right++] = id;
    }
  }
  const std::size_t left = node_index + 1;
  const std::size_t right = left + node_count(middle - begin);
  if (count >= parallel_build_threshold) {
    tbb::parallel_invoke([&] { build(items, halves, begin, middle, left); },
                         [&] { build(items, halves, middle, end, right); });
  } else {
    build(items, halves, begin, middle, left);
    build(items, halves, middle, end, right);
  }
  for (int k = 0; k < 3; ++k) {
    node.lo[k] = std::min(nodes_[left].lo[k], nodes_[right].lo[k]);
    node.hi[k] = std::max(nodes_[left].hi[k], nodes_[right].hi[k]);
  }
  node.first_or_right = std::uint32_t(right);
  node.count = 0;
}

}  // namespace shadowcts
