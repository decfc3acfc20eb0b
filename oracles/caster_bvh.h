#pragma once
// The triangles of a case that can cast a shadow (caster mesh, non-zero area) in a bounding volume
// hierarchy of float boxes, queried conservatively: visit() reports every triangle whose box,
// inflated, may meet a shadow query (shadow_segment.h), so the oracle's candidate set can never
// miss a triangle that meets the query or any query moved by at most the inflation.
//
// Built by median splits along the longest centroid axis: the tree depends only on the case, not
// on the thread count that builds it, and so does the order in which visit() reports triangles.
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

#include "oracles/shadow_segment.h"
#include "shadowcts/case.h"

namespace shadowcts {

class CasterBvh {
 public:
  explicit CasterBvh(const Case& c);

  std::size_t size() const { return triangles_.size(); }
  // The case triangle index of every caster, in leaf order.
  const std::vector<std::uint32_t>& triangles() const { return triangles_; }

  // Calls visit(triangle index) for every caster whose box inflated by `inflation` may meet the
  // query, in a fixed order; stops when visit returns true.
  template <class Visitor>
  void visit(const ShadowSegment& query, double inflation, Visitor&& visit) const;

  // visit() for up to packet_lanes queries at once, which share each node fetch and test it in
  // one loop over the lanes. Calls visit(lane, triangle index) for every lane in exactly the order
  // visit() calls it for that lane's query alone (depth first, left child first, the same box
  // tests); returning true ends that lane only.
  static constexpr int packet_lanes = 16;
  template <class Visitor>
  void visit_packet(const ShadowSegment* queries, int lanes, double inflation,
                    Visitor&& visit) const;

  // The tree and the packet's queries as the vector-lane traversal (caster_bvh_packet.cpp) reads
  // them.
  struct Node {
    float lo[3], hi[3];
    std::uint32_t first_or_right;  // leaf: first triangle slot; inner: right child (left = +1)
    std::uint32_t count;           // triangles in a leaf; 0 for an inner node
  };
  // The queries of visit_packet, lane by lane (structure of arrays for vector loads).
  struct QueryLanes {
    alignas(64) double origin[3][packet_lanes];
    alignas(64) double inverse_direction[3][packet_lanes];
    alignas(64) double zero[3][packet_lanes];  // 1: the direction component is 0
    alignas(64) double padding[packet_lanes];
    alignas(64) double t_max[packet_lanes];
  };
  using LaneVisitor = bool (*)(void* context, int lane, std::uint32_t triangle);

 private:
  struct BuildItem;
  struct SortedItems;
  // visit_packet's traversal, with box_may_meet in vector lanes (Highway, dispatched at run time).
  void visit_lanes(const QueryLanes& q, int lanes, LaneVisitor visit, void* context) const;
  void build(const std::vector<BuildItem>& items, const SortedItems& sorted, std::size_t begin,
             std::size_t end, std::size_t node);

  std::vector<Node> nodes_;
  std::vector<std::uint32_t> triangles_;
  std::vector<Node> leaf_boxes_;  // per triangle slot: the triangle's own box (count unused)
};

template <class Visitor>
void CasterBvh::visit(const ShadowSegment& query, double inflation, Visitor&& visit) const {
  if (nodes_.empty()) return;
  const double padding = box_padding(query, inflation);
  std::uint32_t stack[64];
  int depth = 0;
  stack[depth++] = 0;
  while (depth > 0) {
    const std::uint32_t index = stack[--depth];
    const Node& node = nodes_[index];
    if (!box_may_meet(query, node.lo, node.hi, padding)) continue;
    if (node.count == 0) {
      stack[depth++] = node.first_or_right;
      stack[depth++] = index + 1;  // left child first
      continue;
    }
    for (std::uint32_t slot = node.first_or_right; slot < node.first_or_right + node.count;
         ++slot) {
      const Node& box = leaf_boxes_[slot];
      if (node.count > 1 && !box_may_meet(query, box.lo, box.hi, padding)) continue;
      if (visit(triangles_[slot])) return;
    }
  }
}

template <class Visitor>
void CasterBvh::visit_packet(const ShadowSegment* queries, int lanes, double inflation,
                             Visitor&& visit) const {
  if (nodes_.empty() || lanes <= 0) return;
  QueryLanes q;
  for (int l = 0; l < packet_lanes; ++l) {
    const ShadowSegment& s = queries[l < lanes ? l : 0];  // spare lanes repeat lane 0, unused
    for (int i = 0; i < 3; ++i) {
      q.origin[i][l] = s.origin[i];
      q.inverse_direction[i][l] = s.inverse_direction[i];
      q.zero[i][l] = s.direction[i] == 0.0 ? 1.0 : 0.0;
    }
    q.padding[l] = box_padding(s, inflation);
    q.t_max[l] = s.is_ray ? std::numeric_limits<double>::infinity() : 1.0;
  }
  using V = std::remove_reference_t<Visitor>;
  visit_lanes(
      q, lanes,
      [](void* context, int lane, std::uint32_t triangle) {
        return (*static_cast<V*>(context))(lane, triangle);
      },
      &visit);
}

}  // namespace shadowcts
