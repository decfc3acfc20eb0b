#include "oracles/caster_bvh.h"

#include <algorithm>
#include <utility>

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "oracles/exact_segment_triangle.h"
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
  nodes_.resize(node_count(items.size()));
  triangles_.resize(items.size());
  leaf_boxes_.resize(items.size());
  build(items, 0, items.size(), 0);
}

void CasterBvh::build(std::vector<BuildItem>& items, std::size_t begin, std::size_t end,
                      std::size_t node_index) {
  Node& node = nodes_[node_index];
  float centroid_lo[3], centroid_hi[3];
  for (int k = 0; k < 3; ++k) {
    node.lo[k] = items[begin].lo[k];
    node.hi[k] = items[begin].hi[k];
    centroid_lo[k] = centroid_hi[k] = items[begin].centroid[k];
  }
  for (std::size_t i = begin; i < end; ++i)
    for (int k = 0; k < 3; ++k) {
      node.lo[k] = std::min(node.lo[k], items[i].lo[k]);
      node.hi[k] = std::max(node.hi[k], items[i].hi[k]);
      centroid_lo[k] = std::min(centroid_lo[k], items[i].centroid[k]);
      centroid_hi[k] = std::max(centroid_hi[k], items[i].centroid[k]);
    }
  const std::size_t count = end - begin;
  if (count <= max_leaf_size) {
    node.first_or_right = std::uint32_t(begin);
    node.count = std::uint32_t(count);
    for (std::size_t i = begin; i < end; ++i) {
      triangles_[i] = items[i].triangle;
      Node& box = leaf_boxes_[i];
      std::copy(items[i].lo, items[i].lo + 3, box.lo);
      std::copy(items[i].hi, items[i].hi + 3, box.hi);
      box.first_or_right = 0;
      box.count = 1;
    }
    return;
  }
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if (centroid_hi[k] - centroid_lo[k] > centroid_hi[axis] - centroid_lo[axis]) axis = k;
  const std::size_t middle = begin + count / 2;
  // Ties broken by triangle index: a strict total order makes the split unique.
  std::nth_element(items.begin() + std::ptrdiff_t(begin), items.begin() + std::ptrdiff_t(middle),
                   items.begin() + std::ptrdiff_t(end),
                   [axis](const BuildItem& a, const BuildItem& b) {
                     if (a.centroid[axis] != b.centroid[axis])
                       return a.centroid[axis] < b.centroid[axis];
                     return a.triangle < b.triangle;
                   });
  const std::size_t left = node_index + 1;
  const std::size_t right = left + node_count(middle - begin);
  node.first_or_right = std::uint32_t(right);
  node.count = 0;
  if (count >= parallel_build_threshold) {
    tbb::parallel_invoke([&] { build(items, begin, middle, left); },
                         [&] { build(items, middle, end, right); });
  } else {
    build(items, begin, middle, left);
    build(items, middle, end, right);
  }
}

}  // namespace shadowcts
