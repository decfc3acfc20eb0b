// White-box invariants of the TOP tree: the partition by node planes, the depths, the ancestor
// links, and the canonical planes of shared edges.
#include <algorithm>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "hand_built_case.h"
#include "reference/psv/plane_side.h"
#include "reference/psv/top_tree.h"
#include "reference/psv/top_tree_build.h"
#include "reference/psv/top_tree_depth.h"
#include "shadowcts/hard_shadow_inputs.h"

namespace shadowcts::psv {
namespace {

struct BuiltTree {
  Case c;
  HardShadowLight light;
  std::unique_ptr<PlaneSide> planes;
  BuildStatistics statistics;
  std::vector<std::uint32_t> order;
  TopTree tree;
};

// Every closed mesh may cull (the white-box tests place no sample inside a solid).
std::vector<bool> closed_meshes(const Case& c) {
  std::vector<bool> closed;
  for (const Mesh& m : c.meshes) closed.push_back(m.closed);
  return closed;
}

BuiltTree build(Case c, std::uint64_t seed) {
  BuiltTree b;
  b.c = std::move(c);
  b.light = hard_shadow_light(b.c);
  b.planes = std::make_unique<PlaneSide>(b.light, b.c.triangles, b.c.scale());
  b.order = insertion_order(b.c, *b.planes, closed_meshes(b.c), CasterReach(), seed, b.statistics);
  b.tree = build_top_tree(b.c, *b.planes, b.order, b.statistics);
  return b;
}

// Volumes in the subtree of `node`: its own volume (the triangle sits under its negative chain)
// and everything reachable through positive, negative and intersection children.
std::vector<std::uint32_t> subtree_volumes(const TopTree& tree, std::uint32_t node) {
  std::vector<std::uint32_t> volumes;
  if (node == no_node) return volumes;
  std::vector<std::uint32_t> pending{node};
  std::set<std::uint32_t> seen;
  while (!pending.empty()) {
    const std::uint32_t n = pending.back();
    pending.pop_back();
    if (seen.insert(volume_of(n)).second) volumes.push_back(volume_of(n));
    if (tree.nodes[n].positive != no_node) pending.push_back(tree.nodes[n].positive);
    if (tree.nodes[n].intersection != no_node) pending.push_back(tree.nodes[n].intersection);
    if (!is_capping_node(n)) pending.push_back(n + 1);
  }
  return volumes;
}

std::vector<std::uint32_t> without(std::vector<std::uint32_t> volumes, std::uint32_t volume) {
  volumes.erase(std::remove(volumes.begin(), volumes.end(), volume), volumes.end());
  return volumes;
}

const Triangle& triangle_of(const BuiltTree& b, std::uint32_t volume) {
  return b.c.triangles[volume_triangle(b.tree, volume * nodes_per_volume)];
}

class TopTreeInvariants : public ::testing::TestWithParam<int> {
 protected:
  BuiltTree make() const {
    const ShadowLight light = GetParam() % 2 == 0
                                  ? testing::point_light({1.5f, 10.0f, 0.75f})
                                  : testing::directional_light({0.25f, 1.0f, -0.375f});
    auto h = testing::make_random_case(500 + std::uint64_t(GetParam()), 6, 400, 1.5f, 10, light);
    testing::add_pyramid_fan(h);
    return build(h.c, 7 + std::uint64_t(GetParam()));
  }
};

TEST_P(TopTreeInvariants, ChildrenLieOnTheirSideOfTheNodePlane) {
  const BuiltTree b = make();
  ASSERT_GT(b.statistics.volumes, 100u);
  EXPECT_EQ(b.tree.nodes.size(), b.statistics.volumes * nodes_per_volume);
  std::uint64_t straddling = 0;
  for (std::uint32_t node = 0; node < b.tree.nodes.size(); ++node) {
    const TopNode& n = b.tree.nodes[node];
    for (std::uint32_t v : subtree_volumes(b.tree, n.positive)) {
      EXPECT_EQ(triangle_location(b.tree, *b.planes, node, triangle_of(b, v)), 1)
          << "node " << node << " positive subtree, volume " << v;
      // Strictly: a point on an edge plane searches only the negative side, so a volume that
      // touches the plane (a shared edge or vertex) must not be here.
      if (!is_capping_node(node)) {
        const Triangle& t = triangle_of(b, v);
        for (const glm::vec3& vertex : {t.v0, t.v1, t.v2})
          EXPECT_GT(b.planes->side(b.tree, node, glm::dvec3(vertex)), 0)
              << "node " << node << " positive subtree, volume " << v;
      }
    }
    if (!is_capping_node(node)) {
      for (std::uint32_t v : without(subtree_volumes(b.tree, node + 1), volume_of(node)))
        EXPECT_EQ(triangle_location(b.tree, *b.planes, node, triangle_of(b, v)), -1)
            << "node " << node << " negative subtree, volume " << v;
    }
    // The volume's own triangle lies inside its planes (on the capping plane itself).
    EXPECT_EQ(triangle_location(b.tree, *b.planes, node, triangle_of(b, volume_of(node))), -1);
    // Intersection children: exactly the triangles below `node` that straddle its plane.
    const std::vector<std::uint32_t> below = subtree_volumes(b.tree, n.intersection);
    const std::set<std::uint32_t> in_intersection(below.begin(), below.end());
    for (std::uint32_t v : without(subtree_volumes(b.tree, node), volume_of(node))) {
      const bool straddles = triangle_location(b.tree, *b.planes, node, triangle_of(b, v)) == 0;
      EXPECT_EQ(straddles, in_intersection.count(v) == 1) << "node " << node << ", volume " << v;
      straddling += straddles;
    }
  }
  EXPECT_GT(straddling, 0u);  // the intersection rule was exercised
}

TEST_P(TopTreeInvariants, VolumeDepthIsTheSubtreeMinimum) {
  const BuiltTree b = make();
  for (std::uint32_t first = 0; first < b.tree.nodes.size(); first += nodes_per_volume) {
    float expected = INFINITY;
    for (std::uint32_t v : subtree_volumes(b.tree, first))
      expected = std::min(expected, triangle_light_depth(b.light, triangle_of(b, v)));
    EXPECT_EQ(volume_depth(b.tree, first), expected) << "volume " << volume_of(first);
  }
}

TEST_P(TopTreeInvariants, AncestorLinksClimbThroughIntersectionParentsToTheRoot) {
  const BuiltTree b = make();
  // The expected link of every volume: the innermost node whose intersection child it is below.
  std::vector<std::uint32_t> expected(b.statistics.volumes, no_node - 1);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pending{{b.tree.root, no_node}};
  while (!pending.empty()) {
    const auto [node, ancestor] = pending.back();
    pending.pop_back();
    if (node % nodes_per_volume == 0) expected[volume_of(node)] = ancestor;
    const TopNode& n = b.tree.nodes[node];
    if (n.positive != no_node) pending.push_back({n.positive, ancestor});
    if (n.intersection != no_node) pending.push_back({n.intersection, node});
    if (!is_capping_node(node)) pending.push_back({node + 1, ancestor});
  }
  std::uint64_t nested = 0;
  for (std::uint32_t volume = 0; volume < b.statistics.volumes; ++volume) {
    for (std::uint32_t k = 0; k < nodes_per_volume; ++k)
      EXPECT_EQ(ancestor_link(b.tree, volume * nodes_per_volume + k), expected[volume]);
    // Following the links: every hop lands on a node whose intersection subtree holds where we
    // came from, and the chain ends at the root level.
    std::uint32_t from = volume * nodes_per_volume, hops = 0;
    for (std::uint32_t link = ancestor_link(b.tree, from); link != no_node;
         link = ancestor_link(b.tree, link)) {
      const auto below = subtree_volumes(b.tree, b.tree.nodes[link].intersection);
      EXPECT_NE(std::find(below.begin(), below.end(), volume_of(from)), below.end());
      from = link;
      ASSERT_LE(++hops, b.statistics.volumes);
    }
    nested += hops > 1;
  }
  EXPECT_GT(nested, 0u);  // some intersection subtree lies inside another one
}

INSTANTIATE_TEST_SUITE_P(RandomCases, TopTreeInvariants, ::testing::Range(0, 4));

// An edge shared by two triangles gives the same plane with opposite signs in both, also when
// the vertices tie in x (the public PSV code orders by x only).
TEST(TopTreePlanes, SharedEdgesGiveExactlyOppositePlanes) {
  for (const ShadowLight& light :
       {testing::point_light({0.3f, 9.0f, 0.2f}), testing::directional_light({0.1f, 1.0f, 0.3f})}) {
    auto h = testing::make_hand_built_case(light);
    const glm::vec3 a{0.5f, 2.0f, -1.0f}, b{0.5f, 2.25f, 1.0f};  // same x
    h.add_triangle(a, b, {-1.0f, 2.0f, 0.0f});
    h.add_triangle(b, a, {2.0f, 2.5f, 0.25f});
    h.c.meshes[testing::ground_mesh].caster = false;
    const HardShadowLight hard = hard_shadow_light(h.c);
    const PlaneSide planes(hard, h.c.triangles, h.c.scale());
    TopNode first[4], second[4];
    VolumeSource first_source, second_source;
    planes.make_volume_planes(1, first, first_source);
    planes.make_volume_planes(2, second, second_source);
    // Edge (v0, v1) of the first triangle is edge (v1, v0) of the second: both are edge 0.
    for (int i = 0; i < 4; ++i) EXPECT_EQ(first[0].plane[i], -second[0].plane[i]) << i;
    EXPECT_NE(first[0].plane[0], 0.0f);
  }
}

// The insertion order is a seeded permutation: reproducible, and different seeds differ.
TEST(TopTreeBuild, InsertionOrderIsASeededPermutation) {
  auto h = testing::make_random_case(3, 4, 200, 1.0f, 10, testing::point_light({0, 10, 0}));
  const HardShadowLight light = hard_shadow_light(h.c);
  const PlaneSide planes(light, h.c.triangles, h.c.scale());
  BuildStatistics s1, s2, s3;
  const std::vector<bool> culling = closed_meshes(h.c);
  const auto one = insertion_order(h.c, planes, culling, CasterReach(), 1, s1);
  EXPECT_EQ(one, insertion_order(h.c, planes, culling, CasterReach(), 1, s2));
  const auto other = insertion_order(h.c, planes, culling, CasterReach(), 2, s3);
  EXPECT_NE(one, other);
  auto sorted_one = one, sorted_other = other;
  std::sort(sorted_one.begin(), sorted_one.end());
  std::sort(sorted_other.begin(), sorted_other.end());
  EXPECT_EQ(sorted_one, sorted_other);
  EXPECT_EQ(one.size(), s1.casters);  // nothing culled: no closed mesh, no flat triangle
}

}  // namespace
}  // namespace shadowcts::psv
