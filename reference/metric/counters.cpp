#include "reference/metric/counters.h"

namespace shadowcts::metric {

Counters to_counters(const MetricCounters& counters) {
  const std::uint64_t capsule_share_permille =
      counters.clusters > 0 ? (counters.capsules * 1000 + counters.clusters / 2) / counters.clusters
                            : 0;
  return {{"clusters", counters.clusters},
          {"capsule_share_permille", capsule_share_permille},
          {"clusters_culled_facing_away", counters.clusters_culled_facing_away},
          {"tree_nodes", counters.tree_nodes},
          {"tree_depth", counters.tree_depth},
          {"nodes_visited", counters.traversal.nodes_visited},
          {"clusters_tested_without_hit", counters.traversal.clusters_tested_without_hit},
          {"triangle_tests", counters.traversal.triangle_tests}};
}

}  // namespace shadowcts::metric
