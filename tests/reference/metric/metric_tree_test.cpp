// Tree invariants of both builds: every element is a pivot once; the near / far / overlap subtrees
// of a node hold exactly the elements the partition rule sends there; node light distances are the
// true subtree minima; overlap intervals bound their subtree. And the walk reaches every element
// whose cone holds the query.
#include <algorithm>
#include <limits>

#include <gtest/gtest.h>

#include "metric_test_cases.h"
#include "reference/metric/metric_shadows.h"
#include "reference/metric/traversal.h"
#include "tests/test_name.h"

namespace shadowcts::metric {
namespace {

std::vector<std::uint32_t> subtree_elements(const MetricTree& tree, std::uint32_t root) {
  std::vector<std::uint32_t> elements, stack{root};
  while (!stack.empty()) {
    const MetricTreeNode& node = tree.nodes[stack.back()];
    stack.pop_back();
    elements.push_back(node.pivot);
    for (std::uint32_t child : node.child)
      if (child != no_node) stack.push_back(child);
  }
  return elements;
}

void expect_tree_invariants(const LightStructure& structure) {
  const MetricTree& tree = structure.tree;
  const auto& elements = structure.elements;
  ASSERT_EQ(tree.nodes.size(), elements.size());
  if (tree.nodes.empty()) return;
  std::vector<std::uint32_t> pivots = subtree_elements(tree, 0);
  std::sort(pivots.begin(), pivots.end());
  for (std::uint32_t i = 0; i < pivots.size(); ++i) ASSERT_EQ(pivots[i], i);  // each once

  for (const MetricTreeNode& node : tree.nodes) {
    const LightSpaceElement& pivot = elements[node.pivot];
    double subtree_minimum = pivot.light_distance;
    for (int child = 0; child < 3; ++child) {
      if (node.child[child] == no_node) {
        if (child == int(TreeChild::overlap)) {
          EXPECT_GT(node.overlap_min, node.overlap_max);
        }
        continue;
      }
      for (std::uint32_t e : subtree_elements(tree, node.child[child])) {
        subtree_minimum = std::min(subtree_minimum, elements[e].light_distance);
        const DistanceBounds bounds = element_distance_bounds(structure.frame, pivot, elements[e]);
        ASSERT_EQ(int(partition_child(bounds, node.partition_distance)), child);
        if (child == int(TreeChild::near)) {
          ASSERT_LE(bounds.far, node.partition_distance);
        }
        if (child == int(TreeChild::far)) {
          ASSERT_GT(bounds.near, node.partition_distance);
        }
        if (child == int(TreeChild::overlap)) {
          ASSERT_LE(node.overlap_min, bounds.near);
          ASSERT_GE(node.overlap_max, bounds.far);
        }
      }
    }
    ASSERT_EQ(node.light_distance, subtree_minimum);  // the true minimum, not a bound
  }
}

// The walk must reach every element whose region holds the query: checked against all elements.
void expect_walk_finds_every_holding_element(const LightStructure& structure,
                                             const ViewSamples& samples) {
  std::vector<std::uint32_t> stack;
  for (std::size_t i = 0; i < samples.samples.size(); i += 7) {
    const ViewSample& sample = samples.samples[i];
    if (sample.sample_class != SampleClass::regular) continue;
    const LightSpaceQuery query = make_light_space_query(structure.frame, sample.position);
    std::vector<std::uint32_t> visited;
    TraversalCounters counters;
    for_each_candidate_element(structure.tree, structure.elements, structure.frame, query, counters,
                               stack, [&](std::uint32_t e) {
                                 visited.push_back(e);
                                 return false;
                               });
    std::sort(visited.begin(), visited.end());
    for (std::uint32_t e = 0; e < structure.elements.size(); ++e) {
      const LightSpaceElement& element = structure.elements[e];
      if (pivot_distance(structure.frame, element, query) <= 0.0 &&
          query.light_distance >= element.light_distance) {
        ASSERT_TRUE(std::binary_search(visited.begin(), visited.end(), e))
            << "sample " << i << " misses element " << e;
      }
    }
    EXPECT_LE(counters.nodes_visited, structure.tree.nodes.size());
  }
}

class MetricTreeInvariants : public ::testing::TestWithParam<std::string> {};

TEST_P(MetricTreeInvariants, HoldForBothBuilds) {
  const testing::FixtureCase f = testing::load_fixture(GetParam(), 64);
  for (const char* variant : {"capsules", "median", "spheres16"}) {
    SCOPED_TRACE(variant);
    const MetricOptions options = parse_metric_variant(variant);
    const ClusteredScene scene = cluster_scene(f.c, options);
    const LightStructure structure = build_light_structure(f.c, scene, options);
    expect_tree_invariants(structure);
    expect_walk_finds_every_holding_element(structure, f.samples);
  }
}

INSTANTIATE_TEST_SUITE_P(DefaultFixtures, MetricTreeInvariants,
                         ::testing::ValuesIn(testing::hard_shadow_fixtures()),
                         test_support::param_test_name);

TEST(MetricTree, InsertionHalvesThePartitionDistanceOnNearSteps) {
  const testing::FixtureCase f = testing::load_fixture("gate_house.20k", 8);
  const MetricOptions options;
  const ClusteredScene scene = cluster_scene(f.c, options);
  const LightStructure structure = build_light_structure(f.c, scene, options);
  const double initial = scene_partition_distance(structure.frame, f.c);
  // Walk every root-to-node path: delta is the initial one halved once per near edge.
  std::vector<std::pair<std::uint32_t, double>> stack{{0, initial}};
  while (!stack.empty()) {
    const auto [n, expected] = stack.back();
    stack.pop_back();
    const MetricTreeNode& node = structure.tree.nodes[n];
    ASSERT_EQ(node.partition_distance, expected);
    for (int child = 0; child < 3; ++child)
      if (node.child[child] != no_node)
        stack.push_back(
            {node.child[child], child == int(TreeChild::near) ? expected / 2 : expected});
  }
}

}  // namespace
}  // namespace shadowcts::metric
