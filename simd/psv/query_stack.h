#pragma once
// One step of the PSV / D-PSV query (Mora 2016, Algorithm 1; ref::query_stack) for a group.
#include <algorithm>

#include "simd/psv/query_context.h"

namespace shadowcts::simd::psv {

// A lane whose stack is full ends with stack_overflow (the caller asks the stackless query then).
inline void step_stack(const QueryTree& q, const Group& group, const NodeTests& tests,
                       std::uint32_t capacity, Packet& packet, Worklist& work) {
  const std::uint32_t node = group.node;
  std::uint32_t lanes = group.lanes;
  count_visit(packet, lanes);
  const std::uint32_t positive = located_positive(q, node, tests, lanes, packet);
  for_each_lane(tests.visits_intersection & lanes, [&](std::uint32_t i) {
    std::uint32_t& size = packet.stack_size[i];
    if (size == capacity) {
      packet.answer[i] = ref::QueryAnswer::stack_overflow;
      lanes &= ~(1u << i);
      return;
    }
    packet.stack[i][size++] = q.tree.nodes[node].intersection;
    packet.work[i].stack_high_water = std::max(packet.work[i].stack_high_water, size);
  });
  const std::uint32_t up = positive & lanes;
  // Lanes at a lit leaf continue with their own stacks.
  for_each_lane(up & ~to_positive_child(q, node, tests, up, work), [&](std::uint32_t i) {
    std::uint32_t& size = packet.stack_size[i];
    if (size == 0)
      packet.answer[i] = ref::QueryAnswer::lit;
    else
      work.add(packet.stack[i][--size], false, 1u << i);
  });
  to_negative_child(node, lanes & ~positive, packet, work);
}

}  // namespace shadowcts::simd::psv
