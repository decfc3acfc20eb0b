// The median build of the ternary metric tree, the quality reference of Deves et al. 2018
// (section 6, "Metric tree quality"): pivots selected as Yianilos (1993) proposes, far from the
// other elements, and the median partitioning distance Uhlmann (1991) recommends.
#include <algorithm>
#include <cmath>
#include <random>
#include <utility>

#include "reference/metric/metric_tree.h"
#include "reference/metric/seeded_random.h"

namespace shadowcts::metric {
namespace {

constexpr std::size_t pivot_candidates = 8;
constexpr std::size_t distance_samples = 64;

// The middle of an element's pivot-distance interval; unbounded intervals have none.
bool finite_middle(const DistanceBounds& b, double& middle) {
  if (!std::isfinite(b.near) || !std::isfinite(b.far)) return false;
  middle = 0.5 * (b.near + b.far);
  return true;
}

// Among a few seeded candidates, the element with the largest mean distance to a seeded sample of
// the others. Elements that cover everything never pivot unless nothing else is left: as pivots
// they would separate nothing.
std::size_t choose_pivot(const LightFrame& frame, const std::vector<LightSpaceElement>& elements,
                         const std::vector<std::uint32_t>& members, std::mt19937_64& rng) {
  std::vector<std::size_t> candidates;
  for (std::size_t k = 0; k < pivot_candidates; ++k)
    candidates.push_back(std::size_t(uniform_index(rng, members.size())));
  std::vector<std::size_t> sample;
  for (std::size_t k = 0; k < std::min(distance_samples, members.size()); ++k)
    sample.push_back(std::size_t(uniform_index(rng, members.size())));
  std::size_t best = candidates[0];
  double best_score = -1.0;
  for (std::size_t candidate : candidates) {
    const LightSpaceElement& pivot = elements[members[candidate]];
    if (pivot.covers_everything) continue;
    double sum = 0.0;
    std::size_t count = 0;
    for (std::size_t other : sample) {
      double middle;
      if (other == candidate ||
          !finite_middle(element_distance_bounds(frame, pivot, elements[members[other]]), middle))
        continue;
      sum += middle + pivot.radius;  // the distance between the centres, about
      ++count;
    }
    const double score = count > 0 ? sum / double(count) : 0.0;
    if (score > best_score) {
      best_score = score;
      best = candidate;
    }
  }
  return best;
}

}  // namespace

MetricTree build_metric_tree_by_median(const LightFrame& frame,
                                       const std::vector<LightSpaceElement>& elements,
                                       std::uint64_t seed) {
  MetricTree tree;
  if (elements.empty()) return tree;
  std::mt19937_64 rng(seed);
  struct Work {
    std::uint32_t node;
    std::vector<std::uint32_t> members;
  };
  std::vector<std::uint32_t> all(elements.size());
  for (std::uint32_t i = 0; i < all.size(); ++i) all[i] = i;
  tree.nodes.emplace_back();
  std::vector<Work> stack;
  stack.push_back({0, std::move(all)});
  while (!stack.empty()) {
    Work work = std::move(stack.back());
    stack.pop_back();
    const std::size_t pivot_position = choose_pivot(frame, elements, work.members, rng);
    const std::uint32_t pivot = work.members[pivot_position];
    std::vector<std::uint32_t> rest;
    rest.reserve(work.members.size() - 1);
    for (std::size_t k = 0; k < work.members.size(); ++k)
      if (k != pivot_position) rest.push_back(work.members[k]);

    std::vector<DistanceBounds> bounds(rest.size());
    std::vector<double> middles;
    for (std::size_t k = 0; k < rest.size(); ++k) {
      bounds[k] = element_distance_bounds(frame, elements[pivot], elements[rest[k]]);
      double middle;
      if (finite_middle(bounds[k], middle)) middles.push_back(middle);
    }
    double partition_distance = 0.0;
    if (!middles.empty()) {
      auto median = middles.begin() + std::ptrdiff_t(middles.size() / 2);
      std::nth_element(middles.begin(), median, middles.end());
      partition_distance = *median;
    }

    MetricTreeNode node;
    node.pivot = pivot;
    node.partition_distance = partition_distance;
    node.light_distance = elements[pivot].light_distance;
    std::vector<std::uint32_t> parts[3];
    for (std::size_t k = 0; k < rest.size(); ++k) {
      node.light_distance = std::min(node.light_distance, elements[rest[k]].light_distance);
      const TreeChild child = partition_child(bounds[k], partition_distance);
      if (child == TreeChild::overlap) {
        node.overlap_min = std::min(node.overlap_min, bounds[k].near);
        node.overlap_max = std::max(node.overlap_max, bounds[k].far);
      }
      parts[int(child)].push_back(rest[k]);
    }
    // Child nodes are allocated now and filled when their work item is popped.
    for (int child = 2; child >= 0; --child) {
      if (parts[child].empty()) continue;
      node.child[child] = std::uint32_t(tree.nodes.size());
      tree.nodes.emplace_back();
      stack.push_back({node.child[child], std::move(parts[child])});
    }
    tree.nodes[work.node] = node;
  }
  return tree;
}

}  // namespace shadowcts::metric
