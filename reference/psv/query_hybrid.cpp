#include "reference/psv/query_hybrid.h"

#include <algorithm>

namespace shadowcts::psv {

QueryAnswer query_hybrid(const QueryContext& context, QueryPoint& p,
                         std::span<std::uint32_t> stack_storage, QueryWork& work) {
  const TopTree& tree = context.tree();
  if (tree.root == no_node || context.skipped_by_depth(tree.root, p)) return QueryAnswer::lit;
  NodeStack stack(stack_storage);
  std::uint32_t node = tree.root;
  bool twice = false;
  // While stackless: the node whose intersection child did not fit. The ancestor links inside its
  // intersection subtree lead back to it (or to nodes inside the subtree), never past it.
  std::uint32_t switched_at = no_node;
  while (true) {
    ++work.nodes_visited;
    if (!twice && context.visits_intersection(node, p)) {
      const std::uint32_t intersection = tree.nodes[node].intersection;
      if (switched_at == no_node && !stack.full()) {
        stack.push(intersection);
        work.stack_high_water = std::max(work.stack_high_water, stack.size());
      } else {
        if (switched_at == no_node) {
          ++work.hybrid_switches;
          switched_at = node;
        }
        node = intersection;  // stackless: the intersection subtree first
        continue;
      }
    }
    twice = false;
    if (context.location(node, p) > 0) {
      const std::uint32_t positive = tree.nodes[node].positive;
      if (positive != no_node && !context.skipped_by_depth(positive, p)) {
        node = positive;
      } else if (switched_at != no_node) {
        node = ancestor_link(tree, node);
        twice = true;
        if (node == switched_at) switched_at = no_node;  // back to the short stack
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

}  // namespace shadowcts::psv
