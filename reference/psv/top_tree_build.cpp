#include "reference/psv/top_tree_build.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>

#include "reference/psv/top_tree_depth.h"
#include "shadowcts/float_rounding.h"
#include "shadowcts/geometry/volume_location.h"
#include "shadowcts/hard_shadow_inputs.h"

namespace shadowcts::psv {
// |plane| is linear along the triangle, so its maximum is at a vertex; the error bound makes the
// value an upper bound for the exact plane. A point light divides by the triangle's depth: every
// volume point p = L + s (y - L) has |plane(p)| / |p - L| = |plane(y)| / |y - L|.
float triangle_wedge(const PlaneSide& planes, const TopNode& node, const Triangle& t, float depth) {
  double extent = 0.0;
  for (const glm::vec3& v : {t.v0, t.v1, t.v2}) {
    const glm::dvec3 p(v);
    const double bound = std::fabs(planes.value(node, p)) + planes.error_bound(node, false, p);
    // A plane whose float coefficients overflowed (huge scenes) gives NaN: it must stay NaN (no
    // wedge prunes then), where std::max would drop it.
    if (std::isnan(bound) || bound > extent) extent = bound;
  }
  if (planes.light().directional) return float_above(extent);
  if (!(depth > 0.0f)) return INFINITY;
  return float_above(extent / double(depth) * (1.0 + 0x1p-50));
}

std::vector<std::uint32_t> insertion_order(const Case& c, const PlaneSide& planes,
                                           const std::vector<bool>& face_culling,
                                           const CasterReach& reach, std::uint64_t seed,
                                           BuildStatistics& statistics) {
  std::vector<std::uint32_t> order;
  for (std::size_t i = 0; i < c.triangles.size(); ++i) {
    if (!casts_shadow(c, i)) continue;
    ++statistics.casters;
    const Triangle& t = c.triangles[i];
    // A triangle no sample's segment meets cannot shadow anything (caster_reach.h). First: it
    // is the cheapest test that drops the most.
    if (!reach.may_reach(t.v0, t.v1, t.v2)) {
      ++statistics.culled_out_of_reach;
      continue;
    }
    const int light_side = planes.light_side(t);
    if (light_side == 0) {
      ++statistics.culled_flat;
      continue;
    }
    // Front-face culling (Mora 2016, section 4): in a closed mesh every segment that crosses the
    // solid enters it through a face turned away from the light, so those faces alone cast the
    // mesh's shadow. Which winding is "front" does not matter: the exit faces would do as well.
    // Only where no sample and no light can be inside the solid (face_culling).
    if (face_culling[t.mesh] && light_side > 0) {
      ++statistics.culled_front_facing;
      continue;
    }
    order.push_back(std::uint32_t(i));
  }
  std::mt19937_64 random(seed);
  for (std::size_t i = order.size(); i > 1; --i) std::swap(order[i - 1], order[random() % i]);
  return order;
}

int triangle_location(const TopTree& tree, const PlaneSide& planes, std::uint32_t node,
                      const Triangle& t) {
  bool positive = false, negative = false, on = false;
  for (const glm::vec3& v : {t.v0, t.v1, t.v2}) {
    const int side = planes.side(tree, node, glm::dvec3(v));
    positive = positive || side > 0;
    negative = negative || side < 0;
    on = on || side == 0;
  }
  return geometry::volume_location(positive, negative, on, is_capping_node(node));
}

TopTree build_top_tree(const Case& c, const PlaneSide& planes,
                       const std::vector<std::uint32_t>& order, BuildStatistics& statistics) {
  TopTree tree;
  tree.nodes.reserve(order.size() * nodes_per_volume);
  tree.sources.reserve(order.size());
  std::vector<std::uint32_t> path, intersected;
  for (const std::uint32_t triangle : order) {
    const Triangle& t = c.triangles[triangle];
    const float depth = triangle_light_depth(planes.light(), t);
    // Find the leaf (Algorithm 2, lines 7-22): the parent node and which child slot it is.
    path.clear();
    intersected.clear();
    std::uint32_t ancestor = no_node;  // [stackless] parent of the innermost intersection subtree
    std::uint32_t parent = no_node;
    bool into_intersection = false, dropped = false;
    for (std::uint32_t node = tree.root; node != no_node;) {
      path.push_back(node);
      const int location = triangle_location(tree, planes, node, t);
      parent = node;
      if (location > 0) {
        into_intersection = false;
        node = tree.nodes[node].positive;
      } else if (location < 0) {
        if (is_capping_node(node)) {
          dropped = true;  // the shadow leaf: t lies inside this volume
          break;
        }
        node = node + 1;  // the implicit negative child, never a leaf
      } else {
        into_intersection = true;
        ancestor = node;
        intersected.push_back(node);
        node = tree.nodes[node].intersection;
      }
    }
    if (dropped) {
      ++statistics.dropped_in_shadow;
      continue;
    }
    // Replace the leaf by the triangle's volume (line 23-24).
    const std::uint32_t first = std::uint32_t(tree.nodes.size());
    tree.nodes.resize(tree.nodes.size() + nodes_per_volume);
    tree.sources.emplace_back();
    planes.make_volume_planes(triangle, &tree.nodes[first], tree.sources.back());
    set_volume_depth(tree, first, depth);
    tree.nodes[first + 1].volume_word = ancestor;
    tree.nodes[first + 2].volume_word = triangle;
    if (parent == no_node)
      tree.root = first;
    else if (into_intersection)
      tree.nodes[parent].intersection = first;
    else
      tree.nodes[parent].positive = first;
    // [depth] line 10, applied once the triangle is known to stay in the tree: every volume on
    // its path has it in its subtree.
    for (const std::uint32_t node : path)
      if (depth < volume_depth(tree, node)) set_volume_depth(tree, node, depth);
    // [wedge] the intersection subtrees the triangle entered.
    for (const std::uint32_t node : intersected)
      if (!is_capping_node(node))
        tree.nodes[node].wedge =
            std::max(tree.nodes[node].wedge, triangle_wedge(planes, tree.nodes[node], t, depth));
    ++statistics.volumes;
  }
  statistics.height = tree_height(tree);
  return tree;
}

std::uint64_t tree_height(const TopTree& tree) {
  if (tree.root == no_node) return 0;
  std::uint64_t height = 0;
  std::vector<std::pair<std::uint32_t, std::uint64_t>> pending{{tree.root, 1}};
  while (!pending.empty()) {
    const auto [node, level] = pending.back();
    pending.pop_back();
    height = std::max(height, level);
    const TopNode& n = tree.nodes[node];
    if (n.positive != no_node) pending.push_back({n.positive, level + 1});
    if (n.intersection != no_node) pending.push_back({n.intersection, level + 1});
    if (!is_capping_node(node)) pending.push_back({node + 1, level + 1});
  }
  return height;
}

}  // namespace shadowcts::psv
