#pragma once
// One step of the D-Hybrid query (Mora 2016: a short stack, stackless while it is full;
// ref::query_hybrid) for a group.
#include <algorithm>

#include "simd/psv/query_context.h"

namespace shadowcts::simd::psv {

inline void step_hybrid(const QueryTree& q, const Group& group, const NodeTests& tests,
                        std::uint32_t capacity, Packet& packet, Worklist& work) {
  const std::uint32_t node = group.node;
  count_visit(packet, group.lanes);
  std::uint32_t into = 0;  // lanes that go stackless into the intersection subtree
  const std::uint32_t intersection = q.tree.nodes[node].intersection;
  for_each_lane(group.twice ? 0 : tests.visits_intersection & group.lanes, [&](std::uint32_t i) {
    std::uint32_t& size = packet.stack_size[i];
    if (packet.switched_at[i] == ref::no_node && size < capacity) {
      packet.stack[i][size++] = intersection;
      packet.work[i].stack_high_water = std::max(packet.work[i].stack_high_water, size);
      return;
    }
    if (packet.switched_at[i] == ref::no_node) {
      ++packet.work[i].hybrid_switches;
      packet.switched_at[i] = node;
    }
    into |= 1u << i;
  });
  work.add(intersection, false, into);
  const std::uint32_t lanes = group.lanes & ~into;
  const std::uint32_t positive = located_positive(q, node, tests, lanes, packet);
  const std::uint32_t done = positive & ~to_positive_child(q, node, tests, positive, work);
  const std::uint32_t ancestor = ref::ancestor_link(q.tree, node);
  std::uint32_t back = 0;
  for_each_lane(done, [&](std::uint32_t i) {
    if (packet.switched_at[i] != ref::no_node) {
      back |= 1u << i;
      if (ancestor == packet.switched_at[i]) packet.switched_at[i] = ref::no_node;
      return;
    }
    std::uint32_t& size = packet.stack_size[i];
    if (size == 0)
      packet.answer[i] = ref::QueryAnswer::lit;
    else
      work.add(packet.stack[i][--size], false, 1u << i);
  });
  // (The links inside a stackless stretch always lead back up; no_node would end the sample lit.)
  if (ancestor == ref::no_node)
    finish(packet, back, ref::QueryAnswer::lit);
  else
    work.add(ancestor, true, back);
  to_negative_child(node, lanes & ~positive, packet, work);
}

}  // namespace shadowcts::simd::psv
