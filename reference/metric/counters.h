#pragma once
// Work counters of the reference `metric`, in the order they are reported. All are deterministic
// (sums of integers over samples, or properties of the seeded structures); times are not
// counters and are reported separately (MetricRun in metric_shadows.h).
#include <cstdint>

#include "shadowcts/algorithm.h"

namespace shadowcts::metric {

// Per-sample traversal work (section 6, Fig. 9), summed over samples.
struct TraversalCounters {
  std::uint64_t nodes_visited = 0;
  std::uint64_t clusters_tested_without_hit = 0;  // triangles tested, none blocked
  std::uint64_t triangle_tests = 0;

  TraversalCounters& operator+=(const TraversalCounters& other) {
    nodes_visited += other.nodes_visited;
    clusters_tested_without_hit += other.clusters_tested_without_hit;
    triangle_tests += other.triangle_tests;
    return *this;
  }
};

struct MetricCounters {
  std::uint64_t clusters = 0;
  std::uint64_t capsules = 0;
  std::uint64_t clusters_culled_facing_away = 0;  // normal-cone culling
  std::uint64_t tree_nodes = 0;
  std::uint64_t tree_depth = 0;  // edges on the longest root-to-leaf path
  TraversalCounters traversal;
};

// clusters, capsule_share_permille, clusters_culled_facing_away, tree_nodes, tree_depth,
// nodes_visited, clusters_tested_without_hit, triangle_tests.
Counters to_counters(const MetricCounters& counters);

}  // namespace shadowcts::metric
