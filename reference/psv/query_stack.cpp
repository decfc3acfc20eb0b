#include "reference/psv/query_stack.h"

#include <algorithm>

namespace shadowcts::psv {

QueryAnswer query_stack(const QueryContext& context, QueryPoint& p,
                        std::span<std::uint32_t> stack_storage, QueryWork& work) {
  const TopTree& tree = context.tree();
  if (tree.root == no_node || context.skipped_by_depth(tree.root, p)) return QueryAnswer::lit;
  NodeStack stack(stack_storage);
  std::uint32_t node = tree.root;
  while (node != no_node) {
    ++work.nodes_visited;
    const int location = context.location(node, p);
    // Lines 8-9: the intersection child overlaps both sides; keep it for later.
    if (context.visits_intersection(node, p)) {
      if (stack.full()) return QueryAnswer::stack_overflow;
      stack.push(tree.nodes[node].intersection);
      work.stack_high_water = std::max(work.stack_high_water, stack.size());
    }
    if (location > 0) {
      const std::uint32_t positive = tree.nodes[node].positive;
      if (positive != no_node && !context.skipped_by_depth(positive, p)) {
        node = positive;
      } else {
        // Line 16: a lit leaf; search the intersection subtrees left on the stack.
        if (stack.empty()) return QueryAnswer::lit;
        node = stack.pop();
      }
    } else {
      // Line 22: the negative leaf of a capping plane is inside the volume (of a triangle that
      // shadows p: location() sends p on otherwise).
      if (is_capping_node(node)) return QueryAnswer::shadowed;
      node = node + 1;
    }
  }
  return QueryAnswer::lit;
}

}  // namespace shadowcts::psv
