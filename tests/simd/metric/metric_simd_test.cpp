// The simd `metric` against the reference `metric`: the same light-space elements and the same
// insertion tree node for node (the first difference is named), the same answer for every sample
// and the same counters, on the default fixtures and the reference's stiff cases; independent of
// the thread count, the packet size and the Highway target.
#include <cstring>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <hwy/targets.h>

#include "hand_built_case.h"
#include "metric_test_cases.h"
#include "reference/metric/metric_shadows.h"
#include "simd/metric/metric_algorithm.h"
#include "simd/metric/metric_shadows.h"
#include "simd/metric/metric_tree.h"
#include "simd/metric/traversal.h"
#include "tests/test_name.h"

namespace shadowcts::simd::metric {
namespace {

namespace ref = shadowcts::metric;

const char* const variants[] = {"capsules", "spheres", "capsules16"};

// Empty when the trees are identical, else the first differing node and field.
std::string first_tree_difference(const ref::MetricTree& expected, const ref::MetricTree& actual) {
  if (expected.nodes.size() != actual.nodes.size())
    return "node count " + std::to_string(actual.nodes.size()) + ", expected " +
           std::to_string(expected.nodes.size());
  for (std::size_t i = 0; i < expected.nodes.size(); ++i) {
    const ref::MetricTreeNode &e = expected.nodes[i], &a = actual.nodes[i];
    const auto at = [&](const char* field) { return "node " + std::to_string(i) + ": " + field; };
    if (e.pivot != a.pivot) return at("pivot");
    // Bitwise equality, so that -0 and 0 differ too.
    if (std::memcmp(&e.partition_distance, &a.partition_distance, sizeof(double)) != 0)
      return at("partition_distance");
    for (int c = 0; c < 3; ++c)
      if (e.child[c] != a.child[c]) return at("child");
    if (std::memcmp(&e.light_distance, &a.light_distance, sizeof(double)) != 0)
      return at("light_distance");
    if (std::memcmp(&e.overlap_min, &a.overlap_min, sizeof(double)) != 0) return at("overlap_min");
    if (std::memcmp(&e.overlap_max, &a.overlap_max, sizeof(double)) != 0) return at("overlap_max");
  }
  return {};
}

std::string first_element_difference(const std::vector<ref::LightSpaceElement>& expected,
                                     const std::vector<ref::LightSpaceElement>& actual) {
  if (expected.size() != actual.size())
    return "element count " + std::to_string(actual.size()) + ", expected " +
           std::to_string(expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const ref::LightSpaceElement &e = expected[i], &a = actual[i];
    if (e.cluster != a.cluster || e.centre != a.centre ||
        e.covers_everything != a.covers_everything || e.a != a.a || e.b != a.b ||
        e.radius != a.radius || e.light_distance != a.light_distance ||
        e.arc.normal != a.arc.normal || e.arc.half_length != a.arc.half_length)
      return "element " + std::to_string(i) + " (cluster " + std::to_string(e.cluster) + ")";
  }
  return {};
}

std::string first_sample_difference(const std::vector<std::uint8_t>& expected,
                                    const std::vector<std::uint8_t>& actual) {
  if (expected.size() != actual.size()) return "sample count";
  for (std::size_t i = 0; i < expected.size(); ++i)
    if (expected[i] != actual[i])
      return "sample " + std::to_string(i) + ": " + std::to_string(actual[i]) + ", expected " +
             std::to_string(expected[i]);
  return {};
}

// The simd run against the reference's on one case: answers and counters identical.
void expect_same_as_reference(const Case& c, const ViewSamples& samples, const std::string& variant,
                              std::uint32_t packet = 64, double decision_window = 0x1p-40) {
  SCOPED_TRACE(variant + ", packet " + std::to_string(packet) + ", window " +
               std::to_string(decision_window));
  const ref::MetricRun expected = ref::run_metric(c, samples, ref::parse_metric_variant(variant));
  const PreparedScene scene = prepare_scene(c, samples);
  SimdMetricOptions options = parse_simd_metric_variant(variant);
  options.packet = packet;
  options.decision_window = decision_window;
  const SimdMetricRun actual = run_metric(scene, options);
  EXPECT_EQ(first_sample_difference(expected.output.shadowed, actual.output.shadowed), "");
  EXPECT_EQ(actual.output.counters, expected.output.counters);
}

class SimdMetricOnFixtures : public ::testing::TestWithParam<std::string> {};

// Elements and the insertion tree node for node, from the same clustered scene.
TEST_P(SimdMetricOnFixtures, SameElementsAndTreeNodeForNode) {
  const ref::testing::FixtureCase f = ref::testing::load_fixture(GetParam(), 16);
  const PreparedScene scene = prepare_scene(f.c, f.samples);
  for (const char* variant : variants) {
    SCOPED_TRACE(variant);
    const ref::MetricOptions options = ref::parse_metric_variant(variant);
    const ref::ClusteredScene clustered = ref::cluster_scene(f.c, options);
    const ref::LightStructure expected = ref::build_light_structure(f.c, clustered, options);
    const ref::LightStructure actual = build_light_structure(scene, clustered, options);
    EXPECT_EQ(actual.clusters_culled_facing_away, expected.clusters_culled_facing_away);
    EXPECT_EQ(first_element_difference(expected.elements, actual.elements), "");
    EXPECT_EQ(first_tree_difference(expected.tree, actual.tree), "");
    EXPECT_GT(actual.tree.nodes.size(), 0u);
  }
}

TEST_P(SimdMetricOnFixtures, SameAnswersAndCountersAsTheReference) {
  const ref::testing::FixtureCase f = ref::testing::load_fixture(GetParam(), 96);
  for (const char* variant : variants) expect_same_as_reference(f.c, f.samples, variant);
}

// With a band of 2^-5 (radians, or S in the plane) around every threshold, a large share of the
// lanes is decided by the reference's pivot_distance: the hand-back path and the certain
// decisions around it must still give the reference's walk.
TEST_P(SimdMetricOnFixtures, SameWalkWhenManyLanesAreHandedBack) {
  const ref::testing::FixtureCase f = ref::testing::load_fixture(GetParam(), 48);
  expect_same_as_reference(f.c, f.samples, "capsules", 16, 0x1p-5);
}

INSTANTIATE_TEST_SUITE_P(DefaultFixtures, SimdMetricOnFixtures,
                         ::testing::ValuesIn(ref::testing::hard_shadow_fixtures()),
                         test_support::param_test_name);

// The stiff cases metric's own traps live in (the light a float ulp off a caster's face or 1e-6
// from it, a light inside a cluster, zero-length capsules, coplanar and crease receivers), at
// their own resolution: identical answers.
class SimdMetricOnStiffCases : public ::testing::TestWithParam<std::string> {};

TEST_P(SimdMetricOnStiffCases, SameAnswersAndCountersAsTheReference) {
  ref::testing::FixtureCase f;
  f.c = make_fixture(GetParam());
  if (f.c.light && f.c.light->kind == ShadowLightKind::sun_disk) {
    f.c.light->kind = ShadowLightKind::directional;
    f.c.light->angular_radius = 0.0f;
  }
  f.samples = generate_view_samples(f.c);
  for (const char* variant : variants) expect_same_as_reference(f.c, f.samples, variant);
}

INSTANTIATE_TEST_SUITE_P(
    Stiff, SimdMetricOnStiffCases,
    ::testing::Values("stiff.light_1ulp_off_caster_face", "stiff.light_1e-6_from_caster",
                      "stiff.light_inside_cluster", "stiff.light_near_elongated_caster",
                      "stiff.capsule_zero_length", "stiff.tessellated_convex_sphere",
                      "stiff.walls_on_a_floor", "stiff.light_in_receiver_plane",
                      "stiff.sun_radius_45_degrees"),
    test_support::param_test_name);

// The reference tests' random blockers with samples on shadow-boundary images, the light outside
// and inside the blocker field, point and directional; every packet size.
class SimdMetricOnRandomCases : public ::testing::TestWithParam<int> {};

TEST_P(SimdMetricOnRandomCases, SameAnswersAndCountersAsTheReference) {
  const int k = GetParam();
  const ShadowLight light = k % 3 == 0 ? shadowcts::testing::point_light({1.5f, 10.0f, 0.75f})
                            : k % 3 == 1
                                ? shadowcts::testing::point_light({0.25f, 2.0f, 0.5f})
                                : shadowcts::testing::directional_light({0.25f, 1.0f, -0.375f});
  auto h = shadowcts::testing::make_random_case(500 + std::uint64_t(k), 8, 800, 0.75f, 1500, light);
  for (const char* variant : {"capsules", "spheres4", "capsules16"})
    for (std::uint32_t packet : {8u, 16u, 64u})
      expect_same_as_reference(h.c, h.samples, variant, packet);
}

INSTANTIATE_TEST_SUITE_P(RandomCases, SimdMetricOnRandomCases, ::testing::Range(0, 6));

TEST(SimdMetric, LightInsideVolumesSharedEdgesAndATJunction) {
  // Cones covering every direction (decided per lane by the reference).
  auto inside = shadowcts::testing::make_random_case(
      77, 4, 400, 1.5f, 600, shadowcts::testing::point_light({0.0f, 2.0f, 0.0f}));
  for (const char* variant : variants) expect_same_as_reference(inside.c, inside.samples, variant);

  // A closed fan, a zero-area triangle across the segment, a sample on a receiver's edge and
  // one at the light.
  auto fan =
      shadowcts::testing::make_hand_built_case(shadowcts::testing::point_light({0.5f, 8, 0.5f}));
  shadowcts::testing::add_pyramid_fan(fan);
  fan.add_triangle({-1, 1, 0}, {1, 1, 0}, {0, 1, 0});
  const std::size_t through_edge = fan.add_ground_sample({0.5f, 0, 0.5f});
  fan.add_sample({0.5f, 2.5f, 0.5f}, 3);
  fan.add_ground_sample({0.5f, 8, 0.5f});
  for (const char* variant : variants) expect_same_as_reference(fan.c, fan.samples, variant);
  const AlgorithmOutput output = make_simd_metric()->run(fan.c, fan.samples, "capsules");
  EXPECT_EQ(output.shadowed[through_edge], 1);

  // The T-junction crack of fuzz_watertight-531e78eca2acc5e5: the float test misses both
  // triangles, the exact decision beside the edge finds the blocker.
  const auto [crack, sample] = shadowcts::testing::t_junction_crack();
  for (const char* variant : variants) {
    expect_same_as_reference(crack.c, crack.samples, variant);
    EXPECT_EQ(make_simd_metric()->run(crack.c, crack.samples, variant).shadowed[sample], 1);
  }
}

// Every regular sample lands in exactly one tile, the tile of its pixel (tile_width_of(packet)
// pixels wide, packet / that high), whether the pixels come in order (as the prepared scene gives
// them) or not.
TEST(SimdMetric, SampleTilesHoldEverySampleInItsPixelsTile) {
  const std::uint32_t width = 13;
  for (const bool in_order : {true, false}) {
    RegularSamples samples;
    for (std::uint32_t pixel = 0; pixel < width * 11; pixel += (pixel % 7 == 3 ? 5 : 1))
      samples.index.push_back(pixel);
    if (!in_order) std::swap(samples.index[3], samples.index[samples.index.size() - 4]);
    for (const std::uint32_t packet : {8u, 16u, 64u}) {
      SCOPED_TRACE(std::string(in_order ? "in order" : "out of order") + ", packet " +
                   std::to_string(packet));
      const SampleTiles tiles = sample_tiles(samples, width, packet);
      std::vector<int> seen(samples.size(), 0);
      const std::uint32_t tile_width = tile_width_of(packet);
      const std::uint32_t columns = (width + tile_width - 1) / tile_width;
      for (std::size_t t = 0; t < tiles.size(); ++t) {
        ASSERT_LE(tiles.begin[t + 1] - tiles.begin[t], packet);
        std::uint32_t tile = ~0u;
        for (std::uint32_t k = tiles.begin[t]; k < tiles.begin[t + 1]; ++k) {
          const std::uint32_t i = tiles.samples[k];
          ++seen[i];
          const std::uint32_t pixel = samples.index[i];
          const std::uint32_t expected =
              (pixel / width) / (packet / tile_width) * columns + pixel % width / tile_width;
          if (tile == ~0u) tile = expected;
          EXPECT_EQ(expected, tile) << "sample " << i;
        }
      }
      for (std::size_t i = 0; i < seen.size(); ++i) EXPECT_EQ(seen[i], 1) << "sample " << i;
    }
  }
}

// A tree of identical elements is a chain as deep as it is long: the build must not recurse.
TEST(SimdMetric, TreeOfIdenticalElementsIsTheReferenceChain) {
  ref::LightFrame frame;
  frame.light_position = {0.0, 10.0, 0.0};
  frame.scale = 10.0;
  frame.slack = 1e-10;
  ref::ClusterVolume volume;
  volume.axis_begin = volume.axis_end = {1.0, 0.0, 0.0};
  volume.radius = 0.25;
  std::vector<ref::LightSpaceElement> elements;
  for (std::uint32_t k = 0; k < 5000; ++k)
    elements.push_back(ref::make_light_space_element(frame, volume, k));
  const ref::MetricTree expected = ref::build_metric_tree_by_insertion(frame, elements, 3.0, 7);
  const ref::MetricTree actual =
      simd::metric::build_metric_tree_by_insertion(frame, elements, 3.0, 7);
  EXPECT_EQ(first_tree_difference(expected, actual), "");
}

TEST(SimdMetric, DeterministicForAnyThreadCountAndHighwayTarget) {
  const ref::testing::FixtureCase f = ref::testing::load_fixture("foliage.10k", 64);
  const auto algorithm = make_simd_metric();
  AlgorithmOutput single;
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    single = algorithm->run(f.c, f.samples, "capsules");
  }
  AlgorithmOutput two;
  {
    tbb::global_control both(tbb::global_control::max_allowed_parallelism, 2);
    two = algorithm->run(f.c, f.samples, "capsules");
  }
  EXPECT_EQ(single.shadowed, two.shadowed);
  EXPECT_EQ(single.counters, two.counters);
  // Every other target this build has code for and this CPU runs.
  std::size_t targets = 0;
  for (const std::int64_t target : hwy::SupportedAndGeneratedTargets()) {
    SCOPED_TRACE(hwy::TargetName(target));
    hwy::SetSupportedTargetsForTest(target);
    ASSERT_EQ(traversal_target(), target);
    const AlgorithmOutput other = algorithm->run(f.c, f.samples, "capsules");
    EXPECT_EQ(other.shadowed, single.shadowed);
    EXPECT_EQ(other.counters, single.counters);
    ++targets;
  }
  hwy::SetSupportedTargetsForTest(0);
  EXPECT_GE(targets, 2u);
}

TEST(SimdMetric, DescribesItselfLikeTheReference) {
  const auto algorithm = make_simd_metric();
  const AlgorithmInfo& info = algorithm->info();
  EXPECT_EQ(info.id, "metric");
  EXPECT_EQ(info.backend, "simd");
  EXPECT_EQ(info.variants, (std::vector<std::string>{"capsules", "spheres", "capsules16"}));
  EXPECT_THROW(parse_simd_metric_variant("median"), std::invalid_argument);
  EXPECT_EQ(algorithm->timed_phases("capsules"),
            (std::vector<std::string>{"clustering", "build", "query"}));
}

}  // namespace
}  // namespace shadowcts::simd::metric
