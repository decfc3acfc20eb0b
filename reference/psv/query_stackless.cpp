#include "reference/psv/query_stackless.h"

namespace shadowcts::psv {

QueryAnswer query_stackless(const QueryContext& context, QueryPoint& p, QueryWork& work) {
  const TopTree& tree = context.tree();
  if (tree.root == no_node || context.skipped_by_depth(tree.root, p)) return QueryAnswer::lit;
  std::uint32_t node = tree.root;
  bool twice = false;  // line 3: second visit, the intersection child is done
  while (true) {
    ++work.nodes_visited;
    // Lines 16-18 (the depth test of lines 8-13 is part of visits_intersection: a skipped
    // intersection child would jump straight back here).
    if (!twice && context.visits_intersection(node, p)) {
      node = tree.nodes[node].intersection;
      continue;
    }
    twice = false;
    if (context.location(node, p) > 0) {
      const std::uint32_t positive = tree.nodes[node].positive;
      if (positive != no_node && !context.skipped_by_depth(positive, p)) {
        node = positive;
        continue;
      }
      // Lines 25-28: nothing found in this intersection subtree; back to its parent.
      node = ancestor_link(tree, node);
      if (node == no_node) return QueryAnswer::lit;  // line 40
      twice = true;
    } else {
      if (is_capping_node(node)) return QueryAnswer::shadowed;  // line 34
      node = node + 1;
    }
  }
}

}  // namespace shadowcts::psv
