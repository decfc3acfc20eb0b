#pragma once
// Two-pass load balancing (Sintorn 2014, Section 2.2): the first pass traverses every volume down
// to a predefined level L and, each time it reaches a node there, pushes the job (triangle, node
// key) and goes on with the rest of the upper tree; the second pass picks the jobs up and finishes
// them where the first pass stopped. The shadow mask is the same as one pass's; the counters
// differ only by what the trivial accepts of intervening jobs save.
#include <vector>

#include "reference/ptsv/traversal.h"
#include "reference/ptsv/triangle_setup.h"

namespace shadowcts::ptsv {

// A middle level of the tree: 1 <= level <= leaf_level.
int default_job_level(int leaf_level);

void traverse_two_pass(ClusterTraversal& traversal, const std::vector<ShadowVolume>& volumes,
                       int job_level, TraversalCounters& counters);

}  // namespace shadowcts::ptsv
