#pragma once
// D-Hybrid (Mora 2016, section 3.5): a short stack, and the stackless descent into an
// intersection subtree that does not fit on it until the ancestor links lead back;
// reference/psv/query_hybrid.h step for step.
#include <cstdint>

#include "gpu/emulator/kernel.h"
#include "gpu/psv/query_context.cuh"

namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE {
namespace psv {

__device__ inline QueryAnswer query_hybrid(const QueryContext& context, QueryPoint& p,
                                           NodeStack& stack, QueryWork& work) {
  if (context.root == psv_no_node || context.skipped_by_depth(context.root, p))
    return QueryAnswer::lit;
  const PsvDeviceNode* nodes = context.planes.nodes;
  std::uint32_t node = context.root;
  bool twice = false;
  // While stackless: the node whose intersection child did not fit. The ancestor links inside its
  // intersection subtree lead back to it (or to nodes inside the subtree), never past it.
  std::uint32_t switched_at = psv_no_node;
  while (true) {
    ++work.nodes_visited;
    if (!twice && context.visits_intersection(node, p)) {
      const std::uint32_t intersection = nodes[node].intersection;
      if (switched_at == psv_no_node && !stack.full()) {
        stack.push(intersection);
        if (stack.size() > work.stack_high_water) work.stack_high_water = stack.size();
      } else {
        if (switched_at == psv_no_node) {
          ++work.hybrid_switches;
          switched_at = node;
        }
        node = intersection;  // stackless: the intersection subtree first
        continue;
      }
    }
    twice = false;
    if (context.location(node, p, work) > 0) {
      const std::uint32_t positive = nodes[node].positive;
      if (positive != psv_no_node && !context.skipped_by_depth(positive, p)) {
        node = positive;
      } else if (switched_at != psv_no_node) {
        node = ancestor_link(nodes, node);
        twice = true;
        if (node == switched_at) switched_at = psv_no_node;  // back to the short stack
      } else {
        if (stack.empty()) return QueryAnswer::lit;
        node = stack.pop();
      }
    } else {
      if (is_capping_node(node)) return QueryAnswer::shadowed;
      node = node + 1;
    }
  }
}

}  // namespace psv
}  // namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE
