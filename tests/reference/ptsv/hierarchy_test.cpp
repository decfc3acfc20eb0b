// The cluster hierarchy against a brute-force rebuild, and its explicit bounds and reject reach.
#include "reference/ptsv/hierarchy.h"

#include <algorithm>
#include <map>
#include <utility>

#include <gtest/gtest.h>

#include "ptsv_test_support.h"
#include "reference/ptsv/cluster_keys.h"
#include "reference/ptsv/receiver_rule.h"

namespace shadowcts::ptsv {
namespace {

struct Built {
  ptsv_test::FixtureWithSamples f;
  ClusterKeyLayout layout;
  ClusterKeys keys;
  std::vector<double> reach;  // per sample (ReceiverRule)
};

Built build(const std::string& fixture) {
  Built b;
  b.f = ptsv_test::load_fixture(fixture);
  const ViewFrame frame = make_view_frame(b.f.c.camera, b.f.samples.width, b.f.samples.height);
  const KeyLayoutResult layout =
      make_cluster_key_layout(b.f.c.camera, b.f.samples.width, b.f.samples.height);
  EXPECT_TRUE(layout.problem.empty()) << layout.problem;
  b.layout = layout.layout;
  b.keys = assign_cluster_keys(b.layout, frame, b.f.samples, true);
  EXPECT_TRUE(b.keys.problem.empty()) << b.keys.problem;
  b.reach = ReceiverRule(b.f.c, b.f.samples).reject_reach();
  return b;
}

class HierarchyOnFixture : public ::testing::TestWithParam<const char*> {};

TEST_P(HierarchyOnFixture, ChildMasksEqualABruteForceRebuild) {
  const Built b = build(GetParam());
  const ClusterHierarchy h(b.layout, b.keys.key, b.f.samples, b.reach);
  const int leaves = h.leaf_level();
  // Rebuild: walk every sample's key from the root and set the bit of each step.
  std::map<std::pair<int, std::uint32_t>, std::uint32_t> masks;
  std::size_t regular = 0;
  for (std::uint32_t key : b.keys.key) {
    if (key == no_key) continue;
    ++regular;
    for (int l = 0; l < leaves; ++l) {
      const std::uint64_t node = std::uint64_t(key) >> (5 * (leaves - l));
      const std::uint32_t child = (key >> (5 * (leaves - l - 1))) & 31u;
      masks[{l, std::uint32_t(node)}] |= 1u << child;
    }
  }
  ASSERT_GT(regular, 1000u);
  std::size_t nodes = 0;
  for (int l = 0; l < leaves; ++l) {
    const HierarchyLevel& level = h.level(l);
    for (std::size_t i = 0; i < level.index.size(); ++i) {
      const auto it = masks.find({l, level.index[i]});
      ASSERT_NE(it, masks.end()) << "level " << l << " node " << level.index[i];
      EXPECT_EQ(level.child_mask[i], it->second) << "level " << l << " node " << level.index[i];
      ++nodes;
    }
  }
  EXPECT_EQ(nodes, masks.size());
  // Every sample's path is intact before any traversal.
  for (std::uint32_t key : b.keys.key)
    if (key != no_key) {
      EXPECT_TRUE(h.path_intact(key));
    }
}

TEST_P(HierarchyOnFixture, EveryExplicitBoxContainsItsSamplesAndIsTight) {
  const Built b = build(GetParam());
  const ClusterHierarchy h(b.layout, b.keys.key, b.f.samples, b.reach);
  const int leaves = h.leaf_level();
  std::map<std::pair<int, std::uint32_t>, WorldBox> rebuilt;
  std::map<std::pair<int, std::uint32_t>, double> rebuilt_reach;
  for (std::size_t i = 0; i < b.keys.key.size(); ++i) {
    const std::uint32_t key = b.keys.key[i];
    if (key == no_key) continue;
    const glm::dvec3 p(b.f.samples.samples[i].position);
    for (int l = 0; l <= leaves; ++l) {
      const std::uint32_t node = std::uint32_t(std::uint64_t(key) >> (5 * (leaves - l)));
      const WorldBox& box = h.bounds(l, node);
      for (int k = 0; k < 3; ++k) {
        EXPECT_LE(box.lo[k], p[k]);
        EXPECT_GE(box.hi[k], p[k]);
      }
      double& reach = rebuilt_reach[{l, node}];
      reach = std::max(reach, b.reach[i]);
      auto [it, fresh] = rebuilt.try_emplace({l, node}, WorldBox{p, p});
      if (!fresh) {
        it->second.lo = glm::min(it->second.lo, p);
        it->second.hi = glm::max(it->second.hi, p);
      }
    }
  }
  std::size_t reaching = 0;
  for (const auto& [node, box] : rebuilt) {
    EXPECT_EQ(h.bounds(node.first, node.second).lo, box.lo);
    EXPECT_EQ(h.bounds(node.first, node.second).hi, box.hi);
    const HierarchyLevel& level = h.level(node.first);
    const auto at = std::size_t(h.find(node.first, node.second));
    EXPECT_EQ(level.reject_reach[at], rebuilt_reach.at(node));
    reaching += level.reject_reach[at] > 0.0;
  }
  // About half the samples lie below their receiver's rounded plane.
  EXPECT_GT(reaching, 0u);
}

INSTANTIATE_TEST_SUITE_P(Fixtures, HierarchyOnFixture,
                         ::testing::Values("gate_house.2000", "ground_blockers.2000"));

TEST(ClusterHierarchy, TileListsHoldEveryRegularSampleOnce) {
  const Built b = build("closed_shapes.2000");
  const ClusterHierarchy h(b.layout, b.keys.key, b.f.samples, b.reach);
  std::vector<int> seen(b.f.samples.samples.size(), 0);
  for (std::uint32_t ty = 0; ty < b.layout.tiles_y; ++ty)
    for (std::uint32_t tx = 0; tx < b.layout.tiles_x; ++tx)
      for (const std::uint32_t* s = h.tile_begin(tx, ty); s != h.tile_end(tx, ty); ++s) {
        ++seen[*s];
        EXPECT_EQ(b.f.samples.samples[*s].pixel_x / 8, tx);
        EXPECT_EQ(b.f.samples.samples[*s].pixel_y / 8, ty);
      }
  for (std::size_t i = 0; i < seen.size(); ++i)
    EXPECT_EQ(seen[i], b.keys.key[i] != no_key ? 1 : 0) << "sample " << i;
}

}  // namespace
}  // namespace shadowcts::ptsv
