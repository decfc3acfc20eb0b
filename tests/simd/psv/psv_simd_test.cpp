// The simd `psv` against the reference `psv`: the same TOP tree node for node (the first
// difference is named: which node, which field), the same answer and the same number of nodes
// visited for every sample, and the same counters (exact_plane_tests excepted: it counts each
// port's own exact decisions), for every variant, any thread count and any packet size, on the
// default fixtures, the stiff cases and random scenes at ordinary, tiny and huge scales.
#include <cmath>
#include <cstring>
#include <random>
#include <string>

#include <gtest/gtest.h>
#include <hwy/targets.h>
#include <glm/geometric.hpp>

#include "hand_built_case.h"
#include "metric_test_cases.h"
#include "reference/psv/psv_shadows.h"
#include "shadowcts/errors.h"
#include "shadowcts/fixtures.h"
#include "shadowcts/prepared_scene.h"
#include "simd/psv/psv_algorithm.h"
#include "simd/psv/psv_shadows.h"
#include "tests/test_name.h"

namespace shadowcts::simd::psv {
namespace {

using shadowcts::metric::testing::FixtureCase;
using shadowcts::metric::testing::hard_shadow_fixtures;
using shadowcts::metric::testing::load_fixture;

template <class T>
bool same_bits(const T& a, const T& b) {
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

// Empty when the trees are identical, else the first differing node and field.
std::string first_tree_difference(const ref::TopTree& expected, const ref::TopTree& actual) {
  if (expected.root != actual.root) return "root";
  if (expected.nodes.size() != actual.nodes.size())
    return "node count " + std::to_string(actual.nodes.size()) + ", expected " +
           std::to_string(expected.nodes.size());
  for (std::size_t i = 0; i < expected.nodes.size(); ++i) {
    const ref::TopNode &e = expected.nodes[i], &a = actual.nodes[i];
    const auto at = [&](const char* field) { return "node " + std::to_string(i) + ": " + field; };
    if (!same_bits(e.plane, a.plane)) return at("plane");
    if (e.positive != a.positive) return at("positive child");
    if (e.intersection != a.intersection) return at("intersection child");
    if (!same_bits(e.wedge, a.wedge)) return at("wedge");
    if (e.volume_word != a.volume_word)
      return at(i % 4 == 0 ? "depth" : (i % 4 == 1 ? "ancestor link" : "triangle"));
  }
  if (expected.sources.size() != actual.sources.size()) return "source count";
  for (std::size_t v = 0; v < expected.sources.size(); ++v)
    if (expected.sources[v].edge != actual.sources[v].edge ||
        expected.sources[v].orientation != actual.sources[v].orientation)
      return "volume " + std::to_string(v) + ": source";
  return {};
}

std::string first_statistics_difference(const ref::BuildStatistics& e,
                                        const ref::BuildStatistics& a) {
  if (e.casters != a.casters) return "casters";
  if (e.culled_front_facing != a.culled_front_facing) return "culled_front_facing";
  if (e.culled_flat != a.culled_flat) return "culled_flat";
  if (e.culled_out_of_reach != a.culled_out_of_reach) return "culled_out_of_reach";
  if (e.samples_out_of_reach != a.samples_out_of_reach) return "samples_out_of_reach";
  if (e.dropped_in_shadow != a.dropped_in_shadow) return "dropped_in_shadow";
  if (e.volumes != a.volumes) return "volumes";
  if (e.height != a.height) return "height";
  return {};
}

template <class T>
std::string first_sample_difference(const char* what, const std::vector<T>& expected,
                                    const std::vector<T>& actual) {
  if (expected.size() != actual.size()) return std::string(what) + ": sample count";
  for (std::size_t i = 0; i < expected.size(); ++i)
    if (expected[i] != actual[i])
      return std::string(what) + ": sample " + std::to_string(i) + ": " +
             std::to_string(actual[i]) + ", expected " + std::to_string(expected[i]);
  return {};
}

Counters without_exact_plane_tests(Counters counters) {
  std::erase_if(counters, [](const auto& counter) { return counter.first == "exact_plane_tests"; });
  return counters;
}

// The tree of the simd build against the reference's, on 1 and 2 threads.
void expect_same_tree(Case c, const ViewSamples& samples) {
  const ref::PsvBuild expected = ref::build_psv(c, samples, c.parameters.seed);
  for (const std::uint32_t threads : {1u, 2u}) {
    SCOPED_TRACE(std::to_string(threads) + " threads");
    c.parameters.threads = threads;
    const PreparedScene scene = prepare_scene(c, samples);
    const SimdPsvBuild actual = build_psv(scene, c.parameters.seed);
    EXPECT_EQ(first_tree_difference(expected.tree, actual.build.tree), "");
    EXPECT_EQ(first_statistics_difference(expected.statistics, actual.build.statistics), "");
    EXPECT_EQ(actual.corners.size(), actual.build.statistics.volumes);
    EXPECT_EQ(actual.build.reached, expected.reached);  // the samples to query
  }
}

// Every variant's answers, nodes visited and counters against the reference's.
void expect_same_queries(const Case& c, const ViewSamples& samples,
                         std::initializer_list<std::uint32_t> packets = {1, 5, 16}) {
  const PreparedScene scene = prepare_scene(c, samples);
  for (const std::string& variant : ref::psv_variants()) {
    SCOPED_TRACE(variant);
    ref::PsvOptions options = ref::psv_variant_options(variant);
    options.seed = c.parameters.seed;
    const ref::PsvResult expected = ref::psv_hard_shadows(c, samples, options);
    for (const std::uint32_t packet : packets) {
      SCOPED_TRACE("packet " + std::to_string(packet));
      const SimdPsvResult actual = psv_hard_shadows(scene, {options, packet});
      EXPECT_EQ(first_sample_difference("shadowed", expected.shadowed, actual.shadowed), "");
      EXPECT_EQ(
          first_sample_difference("nodes visited", expected.nodes_visited, actual.nodes_visited),
          "");
      EXPECT_EQ(without_exact_plane_tests(actual.counters),
                without_exact_plane_tests(expected.counters));
    }
  }
}

class SimdPsvOnFixtures : public ::testing::TestWithParam<std::string> {};

TEST_P(SimdPsvOnFixtures, SameTreeNodeForNode) {
  const FixtureCase f = load_fixture(GetParam(), 16);
  expect_same_tree(f.c, f.samples);
}

TEST_P(SimdPsvOnFixtures, SameAnswersVisitsAndCountersForEveryVariant) {
  const FixtureCase f = load_fixture(GetParam(), 64);
  expect_same_queries(f.c, f.samples);
}

INSTANTIATE_TEST_SUITE_P(DefaultFixtures, SimdPsvOnFixtures,
                         ::testing::ValuesIn(hard_shadow_fixtures()),
                         test_support::param_test_name);

// The numerical traps at their own resolution.
class SimdPsvOnStiffCases : public ::testing::TestWithParam<std::string> {};

TEST_P(SimdPsvOnStiffCases, SameTreeAnswersAndCounters) {
  Case c = make_fixture(GetParam());
  if (c.light && c.light->kind == ShadowLightKind::sun_disk) {
    c.light->kind = ShadowLightKind::directional;
    c.light->angular_radius = 0.0f;
  }
  const ViewSamples samples = generate_view_samples(c);
  expect_same_tree(c, samples);
  expect_same_queries(c, samples, {16});
}

std::vector<std::string> stiff_cases_with_a_shadow_light() {
  std::vector<std::string> names;
  for (const std::string& name : stiff_fixtures())
    if (make_fixture(name).light) names.push_back(name);
  return names;
}

INSTANTIATE_TEST_SUITE_P(Stiff, SimdPsvOnStiffCases,
                         ::testing::ValuesIn(stiff_cases_with_a_shadow_light()),
                         test_support::param_test_name);

// Random blockers over a caster ground with samples on shadow boundaries: point lights above and
// inside the blocker field, a directional light; at 2^-60 and 2^60 the float planes lose their
// precision or overflow (infinite and NaN bounds and wedges).
class SimdPsvOnRandomCases : public ::testing::TestWithParam<int> {};

TEST_P(SimdPsvOnRandomCases, SameTreeAnswersAndCounters) {
  const int k = GetParam();
  const ShadowLight light = k % 3 == 0 ? shadowcts::testing::point_light({1.5f, 10.0f, 0.75f})
                            : k % 3 == 1
                                ? shadowcts::testing::point_light({0.25f, 0.5f, 0.5f})
                                : shadowcts::testing::directional_light({0.25f, 1.0f, -0.375f});
  const int exponent = k < 3 ? 0 : (k < 6 ? -60 : 60);
  const auto h = shadowcts::testing::scaled_by_power_of_two(
      shadowcts::testing::make_random_case(700 + std::uint64_t(k), 8, 600, 0.75f, 1200, light),
      exponent);
  expect_same_tree(h.c, h.samples);
  expect_same_queries(h.c, h.samples, {3, 16});
}

INSTANTIATE_TEST_SUITE_P(RandomCases, SimdPsvOnRandomCases, ::testing::Range(0, 9));

// The parallel build's own path: batches that find a leaf already filled by an earlier triangle
// of the same batch resume their descent there. A case where that never happened would leave the
// resumption untested.
TEST(SimdPsvBuild, BatchesResumeDescentsAndStillBuildTheReferenceTree) {
  const FixtureCase f = load_fixture("gate_house.20k", 16);
  const PreparedScene scene = prepare_scene(f.c, f.samples);
  const SimdPsvBuild actual = build_psv(scene, f.c.parameters.seed);
  EXPECT_GT(actual.work.batches, 10u);
  EXPECT_GT(actual.work.resumed_descents, 100u);
  const ref::PsvBuild expected = ref::build_psv(f.c, f.samples, f.c.parameters.seed);
  EXPECT_EQ(first_tree_difference(expected.tree, actual.build.tree), "");
}

// Whether the line test by rounded products is fooled: b - a and p - a exact in double, the
// products of the cross product (b - a) x (p - a) rounded pairwise equal, yet not equal exactly.
bool rounded_products_hide_the_miss(const glm::vec3& a, const glm::vec3& b, const glm::vec3& p) {
  glm::dvec3 u, w;
  for (int i = 0; i < 3; ++i) {
    u[i] = double(b[i]) - double(a[i]);
    w[i] = double(p[i]) - double(a[i]);
    if (u[i] + double(a[i]) != double(b[i]) || w[i] + double(a[i]) != double(p[i]) ||
        double(b[i]) - u[i] != double(a[i]) || double(p[i]) - w[i] != double(a[i]))
      return false;
  }
  bool errors_differ = false;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    const double first = u[i] * w[j], second = u[j] * w[i];
    if (first != second) return false;
    errors_differ = errors_differ || std::fma(u[i], w[j], -first) != std::fma(u[j], w[i], -second);
  }
  return errors_differ;
}

// A vertex p that misses another triangle's edge line (a, b) by less than the rounding of the
// double products that test it: a nearly parallel to b (b scaled by 2^-28 or 2^-29, one
// coordinate a float step off) and p = 2b or b / 2. It lies within every float bound of the edge's
// plane, so the lanes' test by the plane's defining points, or the exact predicate, must decide
// it: the other two vertices of p's triangle lie on one side of the plane, once on each, so one
// of the two scenes has p's triangle straddling the first triangle's plane at the root. Also the
// tiny-coordinate edges whose differences are not even exact in double.
void expect_vertices_just_off_an_edges_line_off_its_plane() {
  std::mt19937 random(11);
  const auto short_float = [&](int lo, int hi) {
    return float(lo + int(random() % unsigned(hi - lo + 1))) / 16.0f;
  };
  int scenes = 0, hidden = 0;
  for (const ShadowLight& light : {shadowcts::testing::point_light({1.5f, 10.0f, 0.75f}),
                                   shadowcts::testing::directional_light({0.25f, 1.0f, -0.375f})}) {
    for (int found = 0; found < 24;) {
      const glm::vec3 b{short_float(-64, 64), short_float(16, 64), short_float(-64, 64)};
      const bool tiny = found % 4 == 3;
      glm::vec3 a = std::ldexp(1.0f, tiny ? -60 : -28 - int(random() % 2)) * b;
      const int axis = int(random() % 3);
      a[axis] = std::nextafter(a[axis], 2.0f * a[axis]);
      const glm::vec3 p = random() % 2 == 0 ? 2.0f * b : 0.5f * b;
      if (!tiny && !rounded_products_hide_the_miss(a, b, p)) continue;
      hidden += tiny ? 0 : 1;
      ++found;
      // The edge's plane: through the light (or along its direction) and the edge.
      const glm::dvec3 along = light.kind == ShadowLightKind::point
                                   ? glm::dvec3(light.position) - glm::dvec3(b)
                                   : glm::dvec3(light.direction);
      const glm::dvec3 normal = glm::normalize(glm::cross(glm::dvec3(b) - glm::dvec3(a), along));
      const glm::vec3 c = b + glm::vec3(0.0f, 0.5f, 0.0f) + glm::vec3(0.25 * normal);
      for (const float side : {1.0f, -1.0f})
        for (const bool edge_first : {true, false}) {
          auto h = shadowcts::testing::make_hand_built_case(light);
          const glm::vec3 d = p + side * glm::vec3(0.5 * normal) + glm::vec3(0.0f, 0.25f, 0.0f);
          const glm::vec3 e = p + side * glm::vec3(0.75 * normal) - glm::vec3(0.125f, 0.0f, 0.25f);
          if (edge_first) {
            h.add_triangle(a, b, c);
            h.add_triangle(p, d, e);
          } else {
            h.add_triangle(p, d, e);
            h.add_triangle(a, b, c);
          }
          h.add_ground_sample({0.5f, 0.0f, 0.25f});
          expect_same_tree(h.c, h.samples);
          ++scenes;
        }
    }
  }
  EXPECT_EQ(hidden, 36);
  EXPECT_EQ(scenes, 192);
}

// On every Highway target: those without fused multiply-adds leave the line test to the scalar
// one.
TEST(SimdPsvBuild, VerticesJustOffAnEdgesLineAreOffItsPlane) {
  for (const std::int64_t target : hwy::SupportedAndGeneratedTargets()) {
    SCOPED_TRACE(hwy::TargetName(target));
    hwy::SetSupportedTargetsForTest(target);
    expect_vertices_just_off_an_edges_line_off_its_plane();
  }
  hwy::SetSupportedTargetsForTest(0);
}

// The build's descents and the queries run in Highway lanes: every target this build has code
// for and this CPU runs builds the reference's tree and gives its answers, on a fixture and on a
// huge-scale case with infinite and NaN bounds.
TEST(SimdPsv, SameTreeAndAnswersOnEveryHighwayTarget) {
  const FixtureCase f = load_fixture("gate_house.20k", 16);
  const auto huge = shadowcts::testing::scaled_by_power_of_two(
      shadowcts::testing::make_random_case(707, 8, 600, 0.75f, 1200,
                                           shadowcts::testing::point_light({1.5f, 10.0f, 0.75f})),
      60);
  std::size_t targets = 0;
  for (const std::int64_t target : hwy::SupportedAndGeneratedTargets()) {
    SCOPED_TRACE(hwy::TargetName(target));
    hwy::SetSupportedTargetsForTest(target);
    expect_same_tree(f.c, f.samples);
    expect_same_queries(f.c, f.samples, {16});
    expect_same_tree(huge.c, huge.samples);
    ++targets;
  }
  hwy::SetSupportedTargetsForTest(0);
  EXPECT_GE(targets, 2u);
}

// Every counter, exact_plane_tests included, and the mask do not depend on the thread count.
TEST(SimdPsv, SameBytesOnOneAndTwoThreads) {
  FixtureCase f = load_fixture("ground_blockers.10k", 48);
  for (const std::string& variant : ref::psv_variants()) {
    SCOPED_TRACE(variant);
    ref::PsvOptions options = ref::psv_variant_options(variant);
    f.c.parameters.threads = 1;
    const SimdPsvResult one = psv_hard_shadows(prepare_scene(f.c, f.samples), {options, 16});
    f.c.parameters.threads = 2;
    const SimdPsvResult two = psv_hard_shadows(prepare_scene(f.c, f.samples), {options, 16});
    EXPECT_EQ(one.shadowed, two.shadowed);
    EXPECT_EQ(one.nodes_visited, two.nodes_visited);
    EXPECT_EQ(one.counters, two.counters);
  }
}

// A receiver that is not a triangle index: the reference's error, naming the view sample, from
// both backends (the port checks the prepared samples).
TEST(SimdPsv, ReceiverOutOfRangeNamesTheViewSample) {
  FixtureCase f = load_fixture("ground_blockers.10k", 48);
  std::size_t bad = 0;
  while (f.samples.samples[bad].sample_class != SampleClass::regular) ++bad;
  f.samples.samples[bad].receiver = std::uint32_t(f.c.triangles.size() + 7);
  const std::string where = "view sample " + std::to_string(bad);
  const auto expect_error = [&](const auto& run) {
    try {
      run();
      ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(where), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("is not a triangle index"), std::string::npos);
    }
  };
  expect_error([&] { ref::build_psv(f.c, f.samples, 1); });
  expect_error([&] { build_psv(prepare_scene(f.c, f.samples), 1); });
}

TEST(SimdPsv, RegisteredWithTheReferenceVariants) {
  const auto algorithm = make_simd_psv();
  EXPECT_EQ(algorithm->info().id, "psv");
  EXPECT_EQ(algorithm->info().backend, "simd");
  EXPECT_EQ(algorithm->info().variants, ref::psv_variants());
}

}  // namespace
}  // namespace shadowcts::simd::psv
