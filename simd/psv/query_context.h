#pragma once
// What the packet queries of the simd psv share. A packet holds up to 16 regular samples (those
// of a 4x4 pixel tile), one per lane; each lane runs the reference's query for its
// sample. Lanes standing on the same node in the same state form a group, and a group is stepped
// as a whole: the node's plane, wedge and depth tests are evaluated for all lanes at once in
// vector lanes (query_packet.cpp), and the reference's branches become lane masks (one step per
// query kind: query_stack.h, query_stackless.h, query_hybrid.h). Only what is a lane's own — a
// plane side the float filter leaves open, the receiver rule, its stack — is handled lane by lane.
// A lane's sequence of nodes is therefore the reference's, and so are its answer and counters.
#include <array>
#include <bit>
#include <cstdint>
#include <vector>

#include "reference/psv/query_context.h"
#include "reference/psv/top_tree.h"
#include "simd/psv/plane_side.h"
#include "simd/psv/top_tree_build.h"

namespace shadowcts::simd::psv {

inline constexpr std::uint32_t max_packet = 16;
// The largest stack of psv_variants() (stack32); the lanes keep their stacks in place.
inline constexpr std::uint32_t max_stack = 32;

struct QueryTree {
  const ref::TopTree& tree;
  const VolumeCornerArray& corners;  // per volume
  const PlaneSide& planes;
  const ref::QueryContext& exact;  // the reference's tests, for what the vector tests leave open
  bool depth_test = false;
  bool directional = false;
};

// One node's tests for the lanes of a packet, as lane bits.
struct NodeTests {
  // The plane's side where the node's error bound decides it (neither bit: the exact test does).
  std::uint32_t positive = 0, negative = 0;
  std::uint32_t visits_intersection = 0;  // ref::QueryContext::visits_intersection
  std::uint32_t positive_skipped = 0;     // a positive child the depth test skips
};

struct Packet {
  alignas(64) double x[max_packet], y[max_packet], z[max_packet], light_depth[max_packet];
  std::uint32_t size = 0;
  ref::QueryPoint point[max_packet];
  ref::QueryWork work[max_packet];
  ref::QueryAnswer answer[max_packet];
  std::uint32_t switched_at[max_packet];  // hybrid: where the short stack was full
  std::uint32_t stack_size[max_packet];
  std::uint32_t stack[max_packet][max_stack];
};

// Lanes standing on the same node in the same state.
struct Group {
  std::uint32_t node = ref::no_node;
  bool twice = false;  // stackless and hybrid: the second visit of the node
  std::uint32_t lanes = 0;
};

// The groups still to step; lanes arriving at the same state join one group.
class Worklist {
 public:
  void add(std::uint32_t node, bool twice, std::uint32_t lanes) {
    if (lanes == 0) return;
    for (std::uint32_t g = 0; g < count_; ++g)
      if (groups_[g].node == node && groups_[g].twice == twice) {
        groups_[g].lanes |= lanes;
        return;
      }
    groups_[count_++] = {node, twice, lanes};
  }
  bool empty() const { return count_ == 0; }
  // The group added last: its node is likely still in the cache. (Taking the smallest node
  // first, so that parted lanes meet again, was 15-25 % slower on foliage.100k and
  // gate_house.100k.)
  Group take() { return groups_[--count_]; }

 private:
  // Every lane is in at most one group.
  std::array<Group, max_packet> groups_{};
  std::uint32_t count_ = 0;
};

template <class F>
inline void for_each_lane(std::uint32_t lanes, F&& f) {
  for (; lanes != 0; lanes &= lanes - 1) f(std::uint32_t(std::countr_zero(lanes)));
}

inline void finish(Packet& packet, std::uint32_t lanes, ref::QueryAnswer answer) {
  for_each_lane(lanes, [&](std::uint32_t i) { packet.answer[i] = answer; });
}

// The lanes of `lanes` whose location (ref::QueryContext::location) at `node` is > 0; the others'
// is <= 0. The vector test decides most; a capping plane's far side asks the reference's rule.
inline std::uint32_t located_positive(const QueryTree& q, std::uint32_t node,
                                      const NodeTests& tests, std::uint32_t lanes, Packet& packet) {
  std::uint32_t positive = tests.positive & lanes;
  // In front of a capping plane the location is 1 whatever the receiver and the rule say.
  const std::uint32_t open =
      ref::is_capping_node(node) ? lanes & ~positive : lanes & ~positive & ~tests.negative;
  for_each_lane(open, [&](std::uint32_t i) {
    const int side =
        ref::is_capping_node(node)
            ? q.exact.location(node, packet.point[i])
            : q.planes.side(q.tree, node, q.planes.node_bound(q.tree.nodes[node], false),
                            q.corners[ref::volume_of(node)], packet.point[i].position);
    if (side > 0) positive |= 1u << i;
  });
  return positive;
}

// Lanes whose sample is not shadowed at a capping node, or moves on from an edge node: to the
// positive child where there is one the depth test does not skip.
inline std::uint32_t to_positive_child(const QueryTree& q, std::uint32_t node,
                                       const NodeTests& tests, std::uint32_t positive,
                                       Worklist& work) {
  const std::uint32_t child = q.tree.nodes[node].positive;
  if (child == ref::no_node) return 0;
  const std::uint32_t go = positive & ~tests.positive_skipped;
  work.add(child, false, go);
  return go;
}

// The negative side: inside the volume at a capping node (shadowed), else the next plane.
inline void to_negative_child(std::uint32_t node, std::uint32_t negative, Packet& packet,
                              Worklist& work) {
  if (ref::is_capping_node(node))
    finish(packet, negative, ref::QueryAnswer::shadowed);
  else
    work.add(node + 1, false, negative);
}

inline void count_visit(Packet& packet, std::uint32_t lanes) {
  for_each_lane(lanes, [&](std::uint32_t i) { ++packet.work[i].nodes_visited; });
}

}  // namespace shadowcts::simd::psv
