#pragma once
// D-Stackless (Mora 2016, Algorithm 3): ancestor links instead of a stack;
// reference/psv/query_stackless.h step for step.
#include <cstdint>

#include "gpu/emulator/kernel.h"
#include "gpu/psv/query_context.cuh"

namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE {
namespace psv {

__device__ inline QueryAnswer query_stackless(const QueryContext& context, QueryPoint& p,
                                              QueryWork& work) {
  if (context.root == psv_no_node || context.skipped_by_depth(context.root, p))
    return QueryAnswer::lit;
  const PsvDeviceNode* nodes = context.planes.nodes;
  std::uint32_t node = context.root;
  bool twice = false;  // line 3: second visit, the intersection child is done
  while (true) {
    ++work.nodes_visited;
    // Lines 16-18 (the depth test of lines 8-13 is part of visits_intersection).
    if (!twice && context.visits_intersection(node, p)) {
      node = nodes[node].intersection;
      continue;
    }
    twice = false;
    if (context.location(node, p, work) > 0) {
      const std::uint32_t positive = nodes[node].positive;
      if (positive != psv_no_node && !context.skipped_by_depth(positive, p)) {
        node = positive;
        continue;
      }
      // Lines 25-28: nothing found in this intersection subtree; back to its parent.
      node = ancestor_link(nodes, node);
      if (node == psv_no_node) return QueryAnswer::lit;  // line 40
      twice = true;
    } else {
      if (is_capping_node(node)) return QueryAnswer::shadowed;  // line 34
      node = node + 1;
    }
  }
}

}  // namespace psv
}  // namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE
