// The parallel insertion-equivalent build of the ternary metric tree (see metric_tree.h).
#include <cmath>
#include <numbers>
#include <random>

#include <glm/geometric.hpp>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_for_each.h>

#include "reference/metric/seeded_random.h"
#include "simd/metric/metric_tree.h"

namespace shadowcts::simd::metric {
namespace {

using shadowcts::metric::CentreKind;
using shadowcts::metric::DistanceBounds;
using shadowcts::metric::LightFrame;
using shadowcts::metric::LightSpaceElement;
using shadowcts::metric::MetricTree;
using shadowcts::metric::MetricTreeNode;
using shadowcts::metric::no_node;
using shadowcts::metric::TreeChild;

// A subtree to build: slots [begin, end) of buffer `buffer` hold its members (Member records in
// insertion order, ascending); the first is its pivot and its node index.
struct Work {
  std::uint32_t begin, end;
  double partition_distance;
  int buffer;
};

// A subtree member as a split reads it, one cache line: the insertion position (the element is
// order[position]) and what the certain classification below and the folds need, so that a split
// streams through contiguous members and gathers a whole element only for the pairs the
// reference's element_distance_bounds decides. cos and sin of the radius are computed once per
// element instead of once per pair.
struct alignas(64) Member {
  glm::dvec3 a{0.0};  // unit direction of a point light's point centre
  double radius = 0.0, cos_radius = 0.0, sin_radius = 0.0;
  double light_distance = 0.0;
  std::uint32_t position = 0;
  bool point_cone = false;  // point light, point centre, not covering everything
};

// Point light, point centres: where the pivot's partition is certain without the reference's
// atan2. The pair's bounds are theta - pr -+ er with theta = atan2(s, c), s = |p x e|, c = p . e
// (unit directions), so far <= delta iff theta <= X1 = delta + pr - er and near > delta iff
// theta > X2 = delta + pr + er. For X in [2^-30, pi - 2^-30], sign(theta - X) is the sign of
// sin(theta - X) = s cos X - c sin X, and cos X, sin X follow from cos and sin of delta + pr (per
// split) and of er (per element) by the addition formulas. Each of these doubles is within a few
// 2^-53 of its exact value, and the reference's far and near within a few ulp of theirs (atan2
// within an ulp): where |s cos X - c sin X| > 2^-40 the reference compares alike. Returns -1 where
// some comparison is not certain (or the pair is not two point cones): the reference decides.
inline int certain_child(double s, double c, double cos_a, double sin_a, const Member& e) {
  constexpr double window = 0x1p-40;
  // X1 = A - er, X2 = A + er.
  const double cos_x1 = cos_a * e.cos_radius + sin_a * e.sin_radius;
  const double sin_x1 = sin_a * e.cos_radius - cos_a * e.sin_radius;
  const double f1 = s * cos_x1 - c * sin_x1;  // > 0: theta > X1, far > delta
  if (f1 < -window) return int(TreeChild::near);
  if (!(f1 > window)) return -1;
  const double cos_x2 = cos_a * e.cos_radius - sin_a * e.sin_radius;
  const double sin_x2 = sin_a * e.cos_radius + cos_a * e.sin_radius;
  const double f2 = s * cos_x2 - c * sin_x2;  // > 0: theta > X2, near > delta
  if (f2 > window) return int(TreeChild::far);
  return -1;  // overlap (its bounds are needed) or unsure
}

// Members of subtrees at least this large have their bounds computed in parallel and their
// children handed to other workers; smaller ones are built on one worker, iteratively (a tree of
// identical elements is a chain as deep as it is long).
constexpr std::uint32_t parallel_members = 2048;

class Builder {
 public:
  Builder(const LightFrame& frame, const std::vector<LightSpaceElement>& elements,
          std::vector<std::uint32_t> order, MetricTree& tree)
      : frame_(frame),
        elements_(elements),
        order_(std::move(order)),
        child_(order_.size()),
        bounds_(order_.size()),
        tree_(tree) {
    for (int b = 0; b < 2; ++b) members_[b].resize(order_.size());
    tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, std::uint32_t(order_.size()), 4096),
                      [&](const tbb::blocked_range<std::uint32_t>& range) {
                        for (std::uint32_t i = range.begin(); i != range.end(); ++i) {
                          const LightSpaceElement& e = elements[order_[i]];
                          Member& m = members_[0][i];
                          m.position = i;
                          m.light_distance = e.light_distance;
                          m.radius = e.radius;
                          m.point_cone = !frame_.directional && e.centre == CentreKind::point &&
                                         !e.covers_everything;
                          if (m.point_cone) {
                            m.a = e.a;
                            m.cos_radius = std::cos(e.radius);
                            m.sin_radius = std::sin(e.radius);
                          }
                        }
                      });
    tree_.nodes.assign(order_.size(), MetricTreeNode{});
  }

  // Partitions one subtree's members into its children, writes its node and returns the
  // children's work (near with half the distance: rule 1; far and overlap keep it: rule 2).
  int split(const Work& work, Work children[3]) {
    const std::vector<Member>& members = members_[work.buffer];
    std::vector<Member>& to_members = members_[1 - work.buffer];
    const Member& pivot_member = members[work.begin];
    const std::uint32_t pivot_position = pivot_member.position;
    const LightSpaceElement& pivot = elements_[order_[pivot_position]];
    // The certain classification needs a point pivot and A = delta + pr with both X = A -+ er in
    // [2^-30, pi - 2^-30] (asked per pair), so that |theta - X| < pi.
    const double a = work.partition_distance + pivot.radius;
    const bool fast = pivot_member.point_cone && a >= 0x1p-30 && a <= std::numbers::pi - 0x1p-30;
    const double cos_a = fast ? std::cos(a) : 0.0, sin_a = fast ? std::sin(a) : 0.0;
    const auto classify = [&](std::uint32_t k) {
      const Member& m = members[k];
      if (fast && m.point_cone) {
        const double x1 = a - m.radius, x2 = a + m.radius;
        if (x1 >= 0x1p-30 && x2 <= std::numbers::pi - 0x1p-30) {
          const glm::dvec3 cross = glm::cross(pivot_member.a, m.a);
          const double s = std::sqrt(glm::dot(cross, cross)), c = glm::dot(pivot_member.a, m.a);
          const int child = certain_child(s, c, cos_a, sin_a, m);
          if (child >= 0) {
            child_[k] = std::uint8_t(child);
            return;
          }
        }
      }
      const DistanceBounds b =
          shadowcts::metric::element_distance_bounds(frame_, pivot, elements_[order_[m.position]]);
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
      node.light_distance = std::min(node.light_distance, members[k].light_distance);
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
    for (std::uint32_t k = work.begin + 1; k < work.end; ++k)
      to_members[next[child_[k]]++] = members[k];
    int children_count = 0;
    for (int c = 0; c < 3; ++c) {
      if (count[c] == 0) continue;
      node.child[c] = to_members[first[c]].position;
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
  const std::vector<LightSpaceElement>& elements_;
  std::vector<std::uint32_t> order_;  // insertion position -> element
  // Two buffers of subtrees' members: a split reads its subtree from one and writes its children
  // to the other.
  std::vector<Member> members_[2];
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
