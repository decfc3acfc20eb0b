#pragma once
// A bounding-volume tree over the light caps in world space, for the receiver half-space rule:
// the caps it may reject for a sample meet the short part of the sample's light segment that is
// not strictly on the light's side of the receiver's plane (receiver_rule.h), so only the caps
// whose boxes overlap that part's box are asked. The boxes are the exact float bounds of the caps'
// vertices; the query is a closed-box overlap test, so no cap meeting the query box is missed.
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "reference/stencil/silhouette.h"

namespace shadowcts::stencil {

class CapTree {
 public:
  explicit CapTree(const std::vector<LightCap>& caps);

  // Calls visit(cap index) for every cap whose box meets the closed box [lo, hi].
  template <class Visit>
  void for_each_overlapping(const glm::dvec3& lo, const glm::dvec3& hi, Visit visit) const {
    if (nodes_.empty()) return;
    std::uint32_t stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes_[stack[--top]];
      if (!overlaps(node.lo, node.hi, lo, hi)) continue;
      if (node.count > 0) {
        for (std::uint32_t k = node.first; k < node.first + node.count; ++k)
          if (overlaps(boxes_[order_[k]].lo, boxes_[order_[k]].hi, lo, hi)) visit(order_[k]);
        continue;
      }
      stack[top++] = node.first;
      stack[top++] = node.first + 1;
    }
  }

 private:
  struct Box {
    glm::dvec3 lo, hi;
  };
  // Inner nodes: children at `first` and `first + 1`, count 0. Leaves: order_[first, first +
  // count).
  struct Node {
    glm::dvec3 lo, hi;
    std::uint32_t first = 0, count = 0;
  };
  static bool overlaps(const glm::dvec3& a_lo, const glm::dvec3& a_hi, const glm::dvec3& b_lo,
                       const glm::dvec3& b_hi) {
    return a_lo.x <= b_hi.x && b_lo.x <= a_hi.x && a_lo.y <= b_hi.y && b_lo.y <= a_hi.y &&
           a_lo.z <= b_hi.z && b_lo.z <= a_hi.z;
  }

  std::vector<Box> boxes_;            // per cap
  std::vector<std::uint32_t> order_;  // cap indices, grouped by leaf
  std::vector<Node> nodes_;           // nodes_[0] is the root
};

}  // namespace shadowcts::stencil
