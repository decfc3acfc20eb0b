#pragma once
// PSV and D-PSV (Mora 2016, Algorithm 1 with the wedge optimization; the depth test where the
// context has it), with a fixed-capacity stack: reference/psv/query_stack.h step for step.
#include <cstdint>

#include "gpu/emulator/kernel.h"
#include "gpu/psv/query_context.cuh"

namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE {
namespace psv {

// lit or shadowed; stack_overflow when an intersection child does not fit on the stack (the
// caller answers that sample with the stackless query).
__device__ inline QueryAnswer query_stack(const QueryContext& context, QueryPoint& p,
                                          NodeStack& stack, QueryWork& work) {
  if (context.root == psv_no_node || context.skipped_by_depth(context.root, p))
    return QueryAnswer::lit;
  const PsvDeviceNode* nodes = context.planes.nodes;
  std::uint32_t node = context.root;
  while (node != psv_no_node) {
    ++work.nodes_visited;
    const int location = context.location(node, p, work);
    // Lines 8-9: the intersection child overlaps both sides; keep it for later.
    if (context.visits_intersection(node, p)) {
      if (stack.full()) return QueryAnswer::stack_overflow;
      stack.push(nodes[node].intersection);
      if (stack.size() > work.stack_high_water) work.stack_high_water = stack.size();
    }
    if (location > 0) {
      const std::uint32_t positive = nodes[node].positive;
      if (positive != psv_no_node && !context.skipped_by_depth(positive, p)) {
        node = positive;
      } else {
        // Line 16: a lit leaf; search the intersection subtrees left on the stack.
        if (stack.empty()) return QueryAnswer::lit;
        node = stack.pop();
      }
    } else {
      // Line 22: the negative leaf of a capping plane is inside the volume of a triangle that
      // shadows p.
      if (is_capping_node(node)) return QueryAnswer::shadowed;
      node = node + 1;
    }
  }
  return QueryAnswer::lit;
}

}  // namespace psv
}  // namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE
