#pragma once
// The ternary metric tree over the light-space elements (Deves et al. 2018, sections 5.1 and
// 5.3). Each node holds a pivot element and a partitioning distance delta; an element goes to the
// near child when its whole region is within delta of the pivot (d_far <= delta), to the far
// child when all of it is beyond (d_near > delta), and to the overlap child otherwise. "Within"
// is measured by pivot_distance (light_space_elements.h).
//
// Two builds: the paper's GPU-style insertion (elements one by one in a seeded order, delta
// halved on every near step), and the CPU median build it is compared with (Yianilos' pivot far
// from the others, Uhlmann's median delta).
#include <cstdint>
#include <limits>
#include <vector>

#include "reference/metric/light_space_elements.h"

namespace shadowcts::metric {

enum class TreeChild : std::uint8_t { near = 0, far = 1, overlap = 2 };

inline constexpr std::uint32_t no_node = std::numeric_limits<std::uint32_t>::max();

struct MetricTreeNode {
  std::uint32_t pivot = 0;                               // index into the element array
  double partition_distance = 0.0;                       // delta
  std::uint32_t child[3] = {no_node, no_node, no_node};  // indexed by TreeChild
  // Smallest light distance of the subtree's elements (section 5.4, step 1): a sample closer to
  // the light than that skips the subtree.
  double light_distance = std::numeric_limits<double>::infinity();
  // [min, max] of pivot_distance over the regions of the overlap subtree's elements (section 5.4,
  // step 3); empty (min > max) without an overlap child.
  double overlap_min = std::numeric_limits<double>::infinity();
  double overlap_max = -std::numeric_limits<double>::infinity();
};

struct MetricTree {
  std::vector<MetricTreeNode> nodes;  // nodes[0] is the root when not empty
};

// The partition rule shared by both builds and the invariant tests.
inline TreeChild partition_child(const DistanceBounds& bounds, double partition_distance) {
  if (bounds.far <= partition_distance) return TreeChild::near;
  if (bounds.near > partition_distance) return TreeChild::far;
  return TreeChild::overlap;
}

// Edges on the longest root-to-leaf path (0 for an empty tree or a lone root).
std::uint64_t tree_depth(const MetricTree& tree);

// The paper's initial partitioning distance: the angular radius of the cone of the scene's
// bounding sphere (its radius in the plane for a directional light; pi when a point light is
// inside it).
double scene_partition_distance(const LightFrame& frame, const Case& c);
// The same from the bounding box [lo, hi] of every caster vertex.
double box_partition_distance(const LightFrame& frame, const glm::dvec3& lo, const glm::dvec3& hi);

// Section 5.3: elements inserted one by one in an order shuffled with `seed`.
MetricTree build_metric_tree_by_insertion(const LightFrame& frame,
                                          const std::vector<LightSpaceElement>& elements,
                                          double initial_partition_distance, std::uint64_t seed);

// The quality reference of section 6 ("Metric tree quality"): recursive, pivot far from the
// others, median partitioning distance.
MetricTree build_metric_tree_by_median(const LightFrame& frame,
                                       const std::vector<LightSpaceElement>& elements,
                                       std::uint64_t seed);

}  // namespace shadowcts::metric
