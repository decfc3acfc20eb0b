#pragma once
// What the four TOP tree queries share: the point being located, its work record, the three
// tests each query makes at a node (plane side, depth test, whether the intersection child needs
// a visit) and the stack the stack and hybrid queries keep.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include <glm/vec3.hpp>

#include "reference/psv/plane_side.h"
#include "reference/psv/top_tree.h"
#include "shadowcts/geometry/receiver_half_space.h"

namespace shadowcts::psv {

struct QueryPoint {
  glm::dvec3 position{0.0};
  std::uint32_t receiver = no_node;  // its triangle never shadows it
  double light_depth = 0.0;          // upper bound on its light distance (top_tree_depth.h)
  // The receiver half-space rule of this point, built when the first volume containing it is
  // found (most points are in none).
  std::optional<geometry::ReceiverHalfSpace> half_space;
};

enum class QueryAnswer { lit, shadowed, stack_overflow };

struct QueryWork {
  std::uint64_t nodes_visited = 0;  // nodes whose plane or links the query read
  std::uint32_t stack_high_water = 0;
  std::uint32_t hybrid_switches = 0;
};

class QueryContext {
 public:
  QueryContext(const TopTree& tree, const PlaneSide& planes, bool depth_test)
      : tree_(tree), planes_(planes), depth_test_(depth_test) {}

  const TopTree& tree() const { return tree_; }

  // > 0: continue in the positive child; otherwise the negative one (a point on a plane belongs
  // to the closed volume, as in the oracle's closed triangles). A capping node is only reached
  // inside its three edge planes, so its negative side means that the triangle meets p's shadow
  // segment. Where that triangle does not shadow p, p counts as in front of it and the search goes
  // on in the positive child, as after a lit leaf: every other volume that holds p is still
  // searched. The triangles the build dropped inside this volume cannot shadow p then either: their
  // hits lie between p and this triangle's hit on the segment, and the receiver's plane side grows
  // monotonically towards the light. A triangle does not shadow p when it is p's receiver, or when
  // the receiver half-space rule rejects it.
  int location(std::uint32_t node, QueryPoint& p) const {
    if (!is_capping_node(node)) return planes_.side(tree_, node, p.position);
    const std::uint32_t triangle = volume_triangle(tree_, node);
    if (triangle == p.receiver) return 1;
    const int side = planes_.side(tree_, node, p.position);
    if (side > 0 || caster_counts(triangle, p)) return side;
    return 1;
  }

  // [depth] Mora 2016, section 3.3: done when the query enters a new volume (a positive or an
  // intersection child, or the root). True when p is closer to the light than every triangle of
  // the subtree.
  bool skipped_by_depth(std::uint32_t volume_first_node, const QueryPoint& p) const {
    return depth_test_ && p.light_depth < double(volume_depth(tree_, volume_first_node));
  }

  // Whether the intersection child of `node` must be searched: it exists, p lies in its wedge
  // (Gerhards et al. 2015) and, with the depth test, is not closer than all of it.
  bool visits_intersection(std::uint32_t node, const QueryPoint& p) const {
    const TopNode& n = tree_.nodes[node];
    if (n.intersection == no_node) return false;
    if (!is_capping_node(node)) {
      const double outside =
          std::fabs(planes_.value(n, p.position)) - planes_.error_bound(n, false, p.position);
      const double wedge =
          planes_.light().directional ? double(n.wedge) : double(n.wedge) * p.light_depth;
      if (outside > wedge) return false;
    }
    return !skipped_by_depth(n.intersection, p);
  }

 private:
  bool caster_counts(std::uint32_t triangle, QueryPoint& p) const {
    if (p.receiver == no_node) return true;  // no receiver, no rule
    const HardShadowLight& light = planes_.light();
    const auto vertex = [](const glm::vec3& v) { return glm::dvec3(v); };
    if (!p.half_space) {
      const Triangle& r = planes_.triangles()[p.receiver];
      p.half_space =
          geometry::receiver_half_space(vertex(r.v0), vertex(r.v1), vertex(r.v2), light.directional,
                                        light.directional ? light.direction : light.position);
    }
    const Triangle& t = planes_.triangles()[triangle];
    return geometry::caster_counts(*p.half_space, p.position, vertex(t.v0), vertex(t.v1),
                                   vertex(t.v2));
  }

  const TopTree& tree_;
  const PlaneSide& planes_;
  bool depth_test_;
};

// The stack of the stack and hybrid queries: at most storage.size() nodes in a buffer the caller
// reuses for every sample of a thread's range (no allocation per query).
class NodeStack {
 public:
  explicit NodeStack(std::span<std::uint32_t> storage) : storage_(storage) {}
  bool empty() const { return size_ == 0; }
  bool full() const { return size_ == storage_.size(); }
  std::uint32_t size() const { return std::uint32_t(size_); }
  void push(std::uint32_t node) { storage_[size_++] = node; }  // requires !full()
  std::uint32_t pop() { return storage_[--size_]; }            // requires !empty()

 private:
  std::span<std::uint32_t> storage_;
  std::size_t size_ = 0;
};

}  // namespace shadowcts::psv
