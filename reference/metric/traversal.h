#pragma once
// Per-sample traversal of the ternary metric tree (Deves et al. 2018, section 5.4): depth test of
// the subtree, pivot cone test, slab test, then the watertight ray-triangle test (Woop, Benthin
// and Wald 2013, include/shadowcts/geometry/segment_triangle.h) on the pivot cluster's triangles
// with an early exit on the first hit; the near or far child by the partitioning distance, and the
// overlap child only when the pivot distance lies in its interval.
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "reference/metric/bounding_volumes.h"
#include "reference/metric/clustering.h"
#include "reference/metric/counters.h"
#include "reference/metric/light_space_elements.h"
#include "reference/metric/metric_tree.h"
#include "shadowcts/case.h"
#include "shadowcts/geometry/receiver_half_space.h"
#include "shadowcts/geometry/segment_triangle.h"
#include "shadowcts/hard_shadow_inputs.h"
#include "shadowcts/view_samples.h"

namespace shadowcts::metric {

struct TraversalScene {
  const Case* c = nullptr;
  // The light as the exact segment/ray-triangle test reads it (shadowcts/geometry/
  // exact_segment_triangle.h), which decides again where the float test misses a triangle whose
  // edge the ray passes within rounding of (ray_near_triangle_edge: a crack at a T-junction).
  HardShadowLight light;
  const Clustering* clustering = nullptr;
  const std::vector<ClusterVolume>* volumes = nullptr;  // per cluster
  const std::vector<LightSpaceElement>* elements = nullptr;
  const MetricTree* tree = nullptr;
  LightFrame frame;
  // Directional light: the length after which a shadow ray has left the scene (slab test).
  double ray_length = 0.0;
};

// Walks the tree for one query and calls visit(element index) for every pivot whose cone holds the
// query and whose depth the query reaches; visit returns true to stop the walk. The walk is the
// whole culling of section 5.4 (steps 1 to 3, without the slabs); returns whether it was stopped.
template <class Visit>
bool for_each_candidate_element(const MetricTree& tree,
                                const std::vector<LightSpaceElement>& elements,
                                const LightFrame& frame, const LightSpaceQuery& query,
                                TraversalCounters& counters, std::vector<std::uint32_t>& stack,
                                Visit&& visit) {
  if (tree.nodes.empty() || query.at_light) return false;
  stack.clear();
  stack.push_back(0);
  while (!stack.empty()) {
    const MetricTreeNode& node = tree.nodes[stack.back()];
    stack.pop_back();
    ++counters.nodes_visited;
    // Step 1: the sample is closer to the light than everything in the subtree.
    if (query.light_distance < node.light_distance) continue;
    const LightSpaceElement& pivot = elements[node.pivot];
    const double distance = pivot_distance(frame, pivot, query);
    // Step 2: inside the pivot's cone (and not in front of it), its cluster may block.
    if (distance <= 0.0 && query.light_distance >= pivot.light_distance && visit(node.pivot))
      return true;
    // Step 3: the overlap child only inside its interval; near and far by delta. Both sides of
    // delta within the slack, so that rounding never drops the side that holds the query.
    const double slack = frame.slack;
    if (node.child[int(TreeChild::overlap)] != no_node && distance >= node.overlap_min - slack &&
        distance <= node.overlap_max + slack)
      stack.push_back(node.child[int(TreeChild::overlap)]);
    if (node.child[int(TreeChild::far)] != no_node && distance >= node.partition_distance - slack)
      stack.push_back(node.child[int(TreeChild::far)]);
    if (node.child[int(TreeChild::near)] != no_node && distance <= node.partition_distance + slack)
      stack.push_back(node.child[int(TreeChild::near)]);
  }
  return false;
}

// Section 5.4, step 2: whether the segment from `from` to `to` meets the cluster's slabs.
bool segment_meets_slabs(const TraversalScene& scene, const ClusterVolume& volume,
                         const glm::dvec3& from, const glm::dvec3& to);

// One caster triangle t (not the sample's receiver) against the sample's shadow segment, as
// sample_is_shadowed decides it: the watertight test, decided again exactly beside an edge, and
// the receiver half-space rule, whose half space is built on first need. Ports call it for the
// triangles their own filters cannot rule out, so that every decision is the reference's.
bool triangle_blocks_sample(const TraversalScene& scene, const ViewSample& sample,
                            const RaySpace& ray_space, std::uint32_t t,
                            std::optional<geometry::ReceiverHalfSpace>& half_space);

// Whether some caster triangle other than the sample's receiver blocks the segment to the point
// light or the ray towards the directional light, by the watertight test, among the clusters of
// the tree, at a point strictly on the light's side of the receiver's plane (the receiver
// half-space rule, decided exactly). `stack` is scratch space reused across samples.
bool sample_is_shadowed(const TraversalScene& scene, const ViewSample& sample,
                        TraversalCounters& counters, std::vector<std::uint32_t>& stack);

}  // namespace shadowcts::metric
