// The parallel insertion-equivalent build of the ternary metric tree (see metric_tree.h).
#include <random>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_for_each.h>

#include "reference/metric/seeded_random.h"
#include "simd/metric/metric_tree.h"

namespace shadowcts::simd::metric {
namespace {

using shadowcts::metric::DistanceBounds;
using shadowcts::metric::LightFrame;
using shadowcts::metric::LightSpaceElement;
using shadowcts::metric::MetricTree;
using shadowcts::metric::MetricTreeNode;
using shadowcts::metric::no_node;
using shadowcts::metric::TreeChild;

// A subtree to build: slots [begin, end) of buffer `buffer` hold its members (their positions in
// the insertion order, ascending, and copies of their elements); the first is its pivot and its
// node index.
struct Work {
  std::uint32_t begin, end;
  double partition_distance;
  int buffer;
};

// Members of subtrees at least this large have their bounds computed in parallel and their
// children handed to other workers; smaller ones are built on one worker, iteratively (a tree of
// identical elements is a chain as deep as it is long).
constexpr std::uint32_t parallel_members = 2048;

class Builder {
 public:
  Builder(const LightFrame& frame, const std::vector<LightSpaceElement>& elements,
          std::vector<std::uint32_t> order, MetricTree& tree)
      : frame_(frame),
        order_(std::move(order)),
        child_(order_.size()),
        bounds_(order_.size()),
        tree_(tree) {
    // The members travel with copies of their elements, so that every split streams through
    // contiguous memory instead of gathering elements from all over the array.
    for (int b = 0; b < 2; ++b) {
      positions_[b].resize(order_.size());
      elements_[b].resize(order_.size());
    }
    tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, std::uint32_t(order_.size()), 4096),
                      [&](const tbb::blocked_range<std::uint32_t>& range) {
                        for (std::uint32_t i = range.begin(); i != range.end(); ++i) {
                          positions_[0][i] = i;
                          elements_[0][i] = elements[order_[i]];
                        }
                      });
    tree_.nodes.assign(order_.size(), MetricTreeNode{});
  }

  // Partitions one subtree's members into its children, writes its node and returns the
  // children's work (near with half the distance: rule 1; far and overlap keep it: rule 2).
  int split(const Work& work, Work children[3]) {
    const std::vector<std::uint32_t>& positions = positions_[work.buffer];
    const std::vector<LightSpaceElement>& elements = elements_[work.buffer];
    std::vector<std::uint32_t>& to_positions = positions_[1 - work.buffer];
    std::vector<LightSpaceElement>& to_elements = elements_[1 - work.buffer];
    const std::uint32_t pivot_position = positions[work.begin];
    const LightSpaceElement& pivot = elements[work.begin];
    const auto classify = [&](std::uint32_t k) {
      const DistanceBounds b =
          shadowcts::metric::element_distance_bounds(frame_, pivot, elements[k]);
      bounds_[k] = b;
      child_[k] = std::uint8_t(shadowcts::metric::partition_child(b, work.partition_distance));
    };
    if (work.end - work.begin >= parallel_members) {
      tbb::parallel_for(tbb::blocked_range<std::uint32_t>(work.begin + 1, work.end, 256),
                        [&](const tbb::blocked_range<std::uint32_t>& range) {
                          for (std::uint32_t k = range.begin(); k != range.end(); ++k) classify(k);
                        });
    } else {
      for (std::uint32_t k = work.begin + 1; k < work.end; ++k) classify(k);
    }
    MetricTreeNode node;
    node.pivot = order_[pivot_position];
    node.partition_distance = work.partition_distance;
    node.light_distance = pivot.light_distance;
    std::uint32_t count[3] = {0, 0, 0};
    // The folds in insertion order, as the insertion build updates the node element by element.
    for (std::uint32_t k = work.begin + 1; k < work.end; ++k) {
      node.light_distance = std::min(node.light_distance, elements[k].light_distance);
      if (child_[k] == std::uint8_t(TreeChild::overlap)) {
        node.overlap_min = std::min(node.overlap_min, bounds_[k].near);
        node.overlap_max = std::max(node.overlap_max, bounds_[k].far);
      }
      ++count[child_[k]];
    }
    // Stable three-way partition into the other buffer: each child keeps its members in
    // insertion order.
    std::uint32_t next[3];
    next[0] = work.begin + 1;
    next[1] = next[0] + count[0];
    next[2] = next[1] + count[1];
    const std::uint32_t first[3] = {next[0], next[1], next[2]};
    for (std::uint32_t k = work.begin + 1; k < work.end; ++k) {
      const std::uint32_t to = next[child_[k]]++;
      to_positions[to] = positions[k];
      to_elements[to] = elements[k];
    }
    int children_count = 0;
    for (int c = 0; c < 3; ++c) {
      if (count[c] == 0) continue;
      node.child[c] = to_positions[first[c]];
      children[children_count++] = {
          first[c], first[c] + count[c],
          c == int(TreeChild::near) ? work.partition_distance * 0.5 : work.partition_distance,
          1 - work.buffer};
    }
    tree_.nodes[pivot_position] = node;
    return children_count;
  }

  // A whole small subtree on this worker.
  void build_serially(const Work& root) {
    std::vector<Work> stack{root};
    Work children[3];
    while (!stack.empty()) {
      const Work work = stack.back();
      stack.pop_back();
      const int n = split(work, children);
      for (int c = 0; c < n; ++c) stack.push_back(children[c]);
    }
  }

  void build(double initial_partition_distance) {
    if (order_.empty()) return;
    const Work root{0, std::uint32_t(order_.size()), initial_partition_distance, 0};
    std::vector<Work> roots{root};
    tbb::parallel_for_each(roots.begin(), roots.end(),
                           [&](const Work& work, tbb::feeder<Work>& feeder) {
                             if (work.end - work.begin < parallel_members) {
                               build_serially(work);
                               return;
                             }
                             Work children[3];
                             const int n = split(work, children);
                             for (int c = 0; c < n; ++c) feeder.add(children[c]);
                           });
  }

 private:
  const LightFrame& frame_;
  std::vector<std::uint32_t> order_;  // insertion position -> element
  // Two buffers of subtrees' members (insertion positions and element copies): a split reads
  // its subtree from one and writes its children to the other.
  std::vector<std::uint32_t> positions_[2];
  std::vector<LightSpaceElement> elements_[2];
  std::vector<std::uint8_t> child_;  // per slot of positions_: the member's TreeChild
  std::vector<DistanceBounds> bounds_;
  MetricTree& tree_;
};

}  // namespace

MetricTree build_metric_tree_by_insertion(const LightFrame& frame,
                                          const std::vector<LightSpaceElement>& elements,
                                          double initial_partition_distance, std::uint64_t seed) {
  // The reference's seeded order (metric_tree_build.cpp): node i is the pivot order[i].
  std::vector<std::uint32_t> order(elements.size());
  for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  std::mt19937_64 rng(seed);
  shadowcts::metric::shuffle(order, rng);
  MetricTree tree;
  Builder builder(frame, elements, std::move(order), tree);
  builder.build(initial_partition_distance);
  return tree;
}

}  // namespace shadowcts::simd::metric
