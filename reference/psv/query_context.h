#pragma once
// What the four TOP tree queries share: the point being located, its work record, and the three
// tests each query makes at a node (plane side, depth test, whether the intersection child needs
// a visit).
#include <cmath>
#include <cstdint>

#include <glm/vec3.hpp>

#include "reference/psv/plane_side.h"
#include "reference/psv/top_tree.h"

namespace shadowcts::psv {

struct QueryPoint {
  glm::dvec3 position{0.0};
  std::uint32_t receiver = no_node;  // its triangle never shadows it
  double light_depth = 0.0;          // upper bound on its light distance (top_tree_depth.h)
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
  // to the closed volume, as in the oracle's closed triangles). On the capping plane of its own
  // receiver a sample counts as in front: the receiver never shadows its sample, and what lies in
  // front of the receiver is still searched.
  int location(std::uint32_t node, const QueryPoint& p) const {
    if (is_capping_node(node) && volume_triangle(tree_, node) == p.receiver) return 1;
    return planes_.side(tree_, node, p.position);
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
  const TopTree& tree_;
  const PlaneSide& planes_;
  bool depth_test_;
};

}  // namespace shadowcts::psv
