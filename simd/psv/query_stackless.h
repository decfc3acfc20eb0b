#pragma once
// One step of the D-Stackless query (Mora 2016, Algorithm 3; ref::query_stackless) for a group.
#include "simd/psv/query_context.h"

namespace shadowcts::simd::psv {

inline void step_stackless(const QueryTree& q, const Group& group, const NodeTests& tests,
                           Packet& packet, Worklist& work) {
  const std::uint32_t node = group.node;
  count_visit(packet, group.lanes);
  // The intersection subtree first; the lanes come back through the ancestor links.
  const std::uint32_t into = group.twice ? 0 : tests.visits_intersection & group.lanes;
  work.add(q.tree.nodes[node].intersection, false, into);
  const std::uint32_t lanes = group.lanes & ~into;
  const std::uint32_t positive = located_positive(q, node, tests, lanes, packet);
  const std::uint32_t back = positive & ~to_positive_child(q, node, tests, positive, work);
  if (back != 0) {
    const std::uint32_t ancestor = ref::ancestor_link(q.tree, node);
    if (ancestor == ref::no_node)
      finish(packet, back, ref::QueryAnswer::lit);
    else
      work.add(ancestor, true, back);
  }
  to_negative_child(node, lanes & ~positive, packet, work);
}

}  // namespace shadowcts::simd::psv
