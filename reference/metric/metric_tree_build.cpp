// The paper's insertion build of the ternary metric tree (Deves et al. 2018, section 5.3).
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include <glm/geometric.hpp>

#include "reference/metric/metric_tree.h"
#include "reference/metric/seeded_random.h"

namespace shadowcts::metric {

double scene_partition_distance(const LightFrame& frame, const Case& c) {
  glm::dvec3 lo(INFINITY), hi(-INFINITY);
  for (const Triangle& t : c.triangles)
    for (const glm::vec3& v : {t.v0, t.v1, t.v2}) {
      lo = glm::min(lo, glm::dvec3(v));
      hi = glm::max(hi, glm::dvec3(v));
    }
  return box_partition_distance(frame, lo, hi);
}

double box_partition_distance(const LightFrame& frame, const glm::dvec3& lo, const glm::dvec3& hi) {
  const glm::dvec3 centre = 0.5 * (lo + hi);
  const double radius = 0.5 * glm::length(hi - lo);
  if (frame.directional) return radius;
  const double distance = glm::length(centre - frame.light_position);
  if (!(distance > radius)) return std::numbers::pi;
  return std::asin(radius / distance);
}

MetricTree build_metric_tree_by_insertion(const LightFrame& frame,
                                          const std::vector<LightSpaceElement>& elements,
                                          double initial_partition_distance, std::uint64_t seed) {
  // On the GPU the scheduler picks the order; a seeded shuffle makes it reproducible.
  std::vector<std::uint32_t> order(elements.size());
  for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  std::mt19937_64 rng(seed);
  shuffle(order, rng);

  MetricTree tree;
  tree.nodes.reserve(elements.size());
  for (std::uint32_t e : order) {
    const LightSpaceElement& element = elements[e];
    double partition_distance = initial_partition_distance;
    MetricTreeNode leaf;
    leaf.pivot = e;
    leaf.light_distance = element.light_distance;
    if (tree.nodes.empty()) {
      leaf.partition_distance = partition_distance;
      tree.nodes.push_back(leaf);
      continue;
    }
    std::uint32_t node = 0;
    while (true) {
      MetricTreeNode& n = tree.nodes[node];
      n.light_distance = std::min(n.light_distance, element.light_distance);
      const DistanceBounds bounds = element_distance_bounds(frame, elements[n.pivot], element);
      const TreeChild child = partition_child(bounds, n.partition_distance);
      // Rule 1: the near region is known to be within delta of the pivot, so an element that
      // enters it halves its own partitioning distance; rule 2: otherwise it keeps it.
      if (child == TreeChild::near) partition_distance *= 0.5;
      if (child == TreeChild::overlap) {
        n.overlap_min = std::min(n.overlap_min, bounds.near);
        n.overlap_max = std::max(n.overlap_max, bounds.far);
      }
      const std::uint32_t next = n.child[int(child)];
      if (next == no_node) {
        // Rule 3: the element becomes the pivot of a new leaf with the distance reached so far.
        leaf.partition_distance = partition_distance;
        n.child[int(child)] = std::uint32_t(tree.nodes.size());
        tree.nodes.push_back(leaf);  // n is not used after this: push_back may move it
        break;
      }
      node = next;
    }
  }
  return tree;
}

}  // namespace shadowcts::metric
