// The four TOP tree queries against each other and against the exact oracle.
#include <cmath>
#include <cstdint>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/vec2.hpp>

#include "hand_built_case.h"
#include "reference/psv/psv_algorithm.h"
#include "reference/psv/psv_shadows.h"
#include "reference/psv/query_stack.h"
#include "reference/psv/top_tree_depth.h"
#include "shadowcts/hard_shadow_comparison.h"
#include "shadowcts/hard_shadow_oracle.h"

namespace shadowcts::psv {
namespace {

std::uint64_t counter(const PsvResult& r, const std::string& name) {
  for (const auto& [key, value] : r.counters)
    if (key == name) return value;
  ADD_FAILURE() << "no counter " << name;
  return 0;
}

PsvResult run(const Case& c, const ViewSamples& samples, QueryKind query,
              std::uint32_t stack_capacity = 12, std::uint64_t seed = 1) {
  PsvOptions options;
  options.query = query;
  options.stack_capacity = stack_capacity;
  options.seed = seed;
  return psv_hard_shadows(c, samples, options);
}

// Robust samples on which the mask differs from the truth.
std::uint64_t robust_mismatches(const std::vector<std::uint8_t>& mask,
                                const HardShadowTruth& truth) {
  const HardShadowComparison comparison = compare_hard_shadows(mask, truth);
  return comparison.leaks + comparison.false_shadows;
}

// Samples that are robust in the truth and differ between two masks.
std::uint64_t robust_differences(const std::vector<std::uint8_t>& a,
                                 const std::vector<std::uint8_t>& b, const HardShadowTruth& truth) {
  std::uint64_t differences = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    differences +=
        (truth.band[i] == BandClass::robust_lit || truth.band[i] == BandClass::robust_shadowed) &&
        a[i] != b[i];
  return differences;
}

testing::HandBuiltCase random_case(int index) {
  const ShadowLight light = index % 2 == 0 ? testing::point_light({1.5f, 10.0f, 0.75f})
                                           : testing::directional_light({0.25f, 1.0f, -0.375f});
  auto h = testing::make_random_case(900 + std::uint64_t(index), 8, 1500, 1.25f, 3000, light);
  testing::add_pyramid_fan(h);
  h.add_ground_sample({0.0f, 0.0f, 0.0f});  // under the fan's apex: through shared edges
  return h;
}

class PsvQueries : public ::testing::TestWithParam<int> {};

TEST_P(PsvQueries, AllQueriesAgreeWithEachOtherAndTheOracle) {
  const auto h = random_case(GetParam());
  const HardShadowTruth truth = exact_hard_shadow_oracle(h.c, h.samples);
  const PsvResult stack = run(h.c, h.samples, QueryKind::stack, 64);
  const PsvResult depth = run(h.c, h.samples, QueryKind::depth, 64);
  const PsvResult stackless = run(h.c, h.samples, QueryKind::stackless);
  const PsvResult hybrid = run(h.c, h.samples, QueryKind::hybrid);
  EXPECT_EQ(robust_mismatches(stack.shadowed, truth), 0u);
  for (const PsvResult* other : {&depth, &stackless, &hybrid}) {
    EXPECT_EQ(robust_differences(stack.shadowed, other->shadowed, truth), 0u);
    EXPECT_EQ(robust_mismatches(other->shadowed, truth), 0u);
  }
  EXPECT_EQ(counter(stack, "stack_overflows"), 0u);
  EXPECT_EQ(counter(depth, "stack_overflows"), 0u);
  std::uint64_t shadowed = 0;
  for (std::uint8_t s : stack.shadowed) shadowed += s;
  EXPECT_GT(shadowed, h.samples.samples.size() / 10);  // not a trivially lit case
  EXPECT_LT(shadowed, h.samples.samples.size() * 9 / 10);
  // The depth test only removes work.
  EXPECT_LE(counter(depth, "nodes_visited_total"), counter(stack, "nodes_visited_total"));
  // The counters are the same for any thread count.
  Case single = h.c;
  single.parameters.threads = 1;
  const PsvResult again = run(single, h.samples, QueryKind::hybrid);
  EXPECT_EQ(again.shadowed, hybrid.shadowed);
  EXPECT_EQ(again.counters, hybrid.counters);
  EXPECT_EQ(again.nodes_visited, hybrid.nodes_visited);
}

TEST_P(PsvQueries, HybridGivesTheSameMaskForEveryStackSizeAndNeverOverflows) {
  const auto h = random_case(GetParam());
  const HardShadowTruth truth = exact_hard_shadow_oracle(h.c, h.samples);
  const PsvResult reference = run(h.c, h.samples, QueryKind::stackless);
  std::uint64_t switches_at_one = 0;
  for (std::uint32_t size : {1u, 4u, 12u, 48u}) {
    const PsvResult hybrid = run(h.c, h.samples, QueryKind::hybrid, size);
    EXPECT_EQ(robust_differences(hybrid.shadowed, reference.shadowed, truth), 0u) << size;
    EXPECT_EQ(robust_mismatches(hybrid.shadowed, truth), 0u) << size;
    EXPECT_EQ(counter(hybrid, "stack_overflows"), 0u) << size;
    EXPECT_LE(counter(hybrid, "stack_high_water"), size);
    if (size == 1) switches_at_one = counter(hybrid, "hybrid_switches");
    if (size == 48) {
      EXPECT_EQ(counter(hybrid, "hybrid_switches"), 0u);
    }
  }
  EXPECT_GT(switches_at_one, 0u);  // the stackless part was exercised
}

TEST_P(PsvQueries, TinyStackReportsOverflowInsteadOfAWrongAnswer) {
  const auto h = random_case(GetParam());
  const HardShadowTruth truth = exact_hard_shadow_oracle(h.c, h.samples);
  const PsvResult tiny = run(h.c, h.samples, QueryKind::stack, 1);
  EXPECT_GT(counter(tiny, "stack_overflows"), 0u);
  EXPECT_LE(counter(tiny, "stack_high_water"), 1u);
  EXPECT_EQ(robust_mismatches(tiny.shadowed, truth), 0u);
  EXPECT_EQ(tiny.shadowed, run(h.c, h.samples, QueryKind::stackless).shadowed);
}

TEST_P(PsvQueries, InsertionOrderChangesNoRobustResult) {
  const auto h = random_case(GetParam());
  const HardShadowTruth truth = exact_hard_shadow_oracle(h.c, h.samples);
  const PsvResult first = run(h.c, h.samples, QueryKind::hybrid, 12, 1);
  for (std::uint64_t seed : {2u, 3u, 12345u}) {
    const PsvResult other = run(h.c, h.samples, QueryKind::hybrid, 12, seed);
    EXPECT_EQ(robust_differences(first.shadowed, other.shadowed, truth), 0u) << seed;
    // A different tree: the work differs, the answer does not.
    EXPECT_NE(first.nodes_visited, other.nodes_visited) << seed;
  }
}

INSTANTIATE_TEST_SUITE_P(RandomCases, PsvQueries, ::testing::Range(0, 4));

// Figure 3 of Mora 2016: lit points closer to the light than every occluder. A point light behind
// the camera, a field of floating quads beyond the visible near ground: PSV scans the tree for
// the near ground, D-PSV stops at the root. Those samples are also out of every quad's reach
// (samples_out_of_reach), so psv_hard_shadows does not query them at all: the two queries are
// asked directly here.
TEST(PsvDepthTest, FewerNodesForLitSamplesWithTheLightBehindTheCamera) {
  Case c;
  c.name = "light_behind_camera";
  c.source = "psv_query_test.cpp";
  c.meshes = {Mesh{"ground", false, false}, Mesh{"quads", false, true}};
  c.triangles.push_back({{-60, 0, -60}, {60, 0, -60}, {0, 0, 60}, 0});
  std::mt19937_64 random(5);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int i = 0; i < 600; ++i) {
    const glm::vec3 centre{-20.0f + 40.0f * unit(random), 1.0f + 3.0f * unit(random),
                           -40.0f + 35.0f * unit(random)};
    const glm::vec3 u{0.8f, 0.3f * (unit(random) - 0.5f), 0.0f};
    const glm::vec3 v{0.3f * (unit(random) - 0.5f), 0.8f, 0.3f * (unit(random) - 0.5f)};
    c.triangles.push_back({centre - u - v, centre + u - v, centre + u + v, 1});
    c.triangles.push_back({centre - u - v, centre + u + v, centre - u + v, 1});
  }
  ShadowLight light;
  light.position = {0.0f, 12.0f, 40.0f};
  c.light = light;
  c.camera.position = {0.0f, 8.0f, 30.0f};
  c.camera.target = {0.0f, 0.0f, -10.0f};
  c.camera.far_plane = 200.0f;
  c.camera.width = c.camera.height = 128;
  validate(c);
  const ViewSamples samples = generate_view_samples(c);
  const HardShadowTruth truth = exact_hard_shadow_oracle(c, samples);
  const PsvResult psv = run(c, samples, QueryKind::stack, 64);
  const PsvResult dpsv = run(c, samples, QueryKind::depth, 64);
  EXPECT_EQ(robust_mismatches(psv.shadowed, truth), 0u);
  EXPECT_EQ(dpsv.shadowed, psv.shadowed);
  const PsvBuild build = build_psv(c, samples, 1);
  const QueryContext plain(build.tree, *build.planes, false);
  const QueryContext depth_tested(build.tree, *build.planes, true);
  std::vector<std::uint32_t> stack(64);
  EXPECT_GT(counter(psv, "samples_out_of_reach"), 0u);
  // Nearer to the light than every vertex of a quad: nearer than every occluder.
  double nearest = INFINITY;
  for (std::size_t t = 1; t < c.triangles.size(); ++t)
    for (const glm::vec3& v : {c.triangles[t].v0, c.triangles[t].v1, c.triangles[t].v2})
      nearest = std::min(nearest, double(glm::distance(v, light.position)));
  std::uint64_t lit = 0, shadowed = 0, psv_lit_nodes = 0, dpsv_lit_nodes = 0;
  for (std::size_t i = 0; i < samples.samples.size(); ++i) {
    if (samples.samples[i].sample_class != SampleClass::regular) continue;
    if (psv.shadowed[i]) {
      ++shadowed;
      continue;
    }
    if (!(glm::distance(samples.samples[i].position, light.position) < nearest * 0.999)) continue;
    ++lit;
    QueryPoint p;
    p.position = glm::dvec3(samples.samples[i].position);
    p.receiver = samples.samples[i].receiver;
    p.light_depth = sample_light_depth(build.light, p.position);
    QueryWork without, with;
    EXPECT_EQ(query_stack(plain, p, stack, without), QueryAnswer::lit);
    EXPECT_EQ(query_stack(depth_tested, p, stack, with), QueryAnswer::lit);
    psv_lit_nodes += without.nodes_visited;
    dpsv_lit_nodes += with.nodes_visited;
  }
  ASSERT_GT(lit, 500u);
  ASSERT_GT(shadowed, 100u);
  EXPECT_LT(dpsv_lit_nodes * 2, psv_lit_nodes);
  std::cout << "light behind the camera: " << lit << " lit samples, nodes visited per lit sample "
            << double(psv_lit_nodes) / double(lit) << " (PSV) vs "
            << double(dpsv_lit_nodes) / double(lit) << " (D-PSV)\n";
  ::testing::Test::RecordProperty("psv_nodes_per_lit_sample", std::to_string(psv_lit_nodes / lit));
  ::testing::Test::RecordProperty("dpsv_nodes_per_lit_sample",
                                  std::to_string(dpsv_lit_nodes / lit));
}

TEST(PsvAlgorithm, DescribesItselfAndRejectsUnknownVariants) {
  const auto algorithm = make_psv();
  const AlgorithmInfo& info = algorithm->info();
  EXPECT_EQ(info.id, "psv");
  EXPECT_EQ(info.backend, "reference");
  EXPECT_EQ(info.variants, (std::vector<std::string>{"stack", "stack32", "depth", "stackless",
                                                     "hybrid", "hybrid4"}));
  EXPECT_TRUE(info.capabilities.point_light);
  EXPECT_TRUE(info.capabilities.directional_light);
  EXPECT_FALSE(info.capabilities.sun_disk);
  auto h = testing::make_hand_built_case(testing::point_light({0, 8, 0}));
  testing::add_pyramid_fan(h);
  h.add_ground_sample({0, 0, 0});
  EXPECT_THROW(algorithm->run(h.c, h.samples, "stack7"), std::invalid_argument);
  const AlgorithmOutput output = algorithm->run(h.c, h.samples, "stack32");
  EXPECT_EQ(output.shadowed, std::vector<std::uint8_t>{1});
  ASSERT_FALSE(output.counters.empty());
  EXPECT_EQ(output.counters.front().first, "triangles_inserted");
}

// The receiver never shadows its own sample (even exactly on its plane), zero-area triangles never
// shadow, and a triangle meeting the segment (closed) shadows it, but not where it meets it only
// in the receiver's plane (the receiver half-space rule): a sample on the fan's edge is lit.
TEST(PsvSemantics, ReceiverZeroAreaAndClosedTriangles) {
  auto h = testing::make_hand_built_case(testing::point_light({0.5f, 8, 0.5f}));
  testing::add_pyramid_fan(h);
  h.add_triangle({-1, 1, 0}, {1, 1, 0}, {0, 1, 0});  // zero area, across the segment
  const std::size_t through_edge = h.add_ground_sample({0.5f, 0, 0.5f});
  const std::size_t on_receiver = h.add_sample({0.5f, 2.5f, 0.5f}, 3);    // on the fan's edge
  const std::size_t on_own_face = h.add_sample({0.0f, 2.75f, 0.25f}, 3);  // exactly on it
  const std::size_t unblocked = h.add_ground_sample({6.0f, 0, -6.0f});
  const HardShadowTruth truth = exact_hard_shadow_oracle(h.c, h.samples);
  EXPECT_EQ(truth.shadowed[on_own_face], 0);
  EXPECT_EQ(truth.shadowed[on_receiver], 0);
  for (QueryKind query :
       {QueryKind::stack, QueryKind::depth, QueryKind::stackless, QueryKind::hybrid}) {
    const PsvResult r = run(h.c, h.samples, query);
    EXPECT_EQ(r.shadowed[through_edge], 1);
    EXPECT_EQ(r.shadowed[on_receiver], 0);  // triangle 2 meets it only at p
    EXPECT_EQ(r.shadowed[unblocked], 0);
    EXPECT_EQ(r.shadowed[on_own_face], 0);
  }
}

// Found by fuzz_degenerate at a scale of 2^-47: the planes are stored in float, and a plane's
// offset (a product of three coordinates, ~2^-143) was a subnormal whose absolute rounding the
// error bound ignored, so a sample landed on the wrong side of its receiver's neighbour without
// the exact fallback (a false shadow). The bound covers subnormal rounding now; tiny and huge
// scenes agree with the oracle.
TEST(PsvSemantics, TinyAndHugeScenesAgreeWithTheOracle) {
  auto h =
      testing::make_hand_built_case(testing::point_light({-0x1.78p-51f, 0x1.91p-48f, -0x1.ap-49f}));
  h.c.triangles.clear();
  h.add_triangle({-0x1.3p-50f, 0x1.f4p-50f, -0x1.ep-52f}, {-0x1.38p-51f, -0x1.6cp-50f, -0x1.dp-52f},
                 {-0x1.8p-55f, 0x1.ep-50f, -0x1.ap-53f});
  const std::uint32_t receiver =
      h.add_triangle({-0x1.84p-50f, -0x1.18p-51f, -0x1p-55f}, {-0x1p-50f, 0x1.2cp-50f, 0x1.98p-50f},
                     {0x1.a8p-50f, 0x1.ap-53f, -0x1p-49f});
  h.c.camera.position = {-0x1.b80b06p-52f, 0x1.ff3e78p-49f, -0x1.0c59bap-49f};
  h.c.camera.target = {0, 0, 0};
  const std::size_t sample = h.add_sample({-0x1.528p-50f, 0x1.9p-54f, 0x1.28p-51f}, receiver);
  const HardShadowTruth truth = exact_hard_shadow_oracle(h.c, h.samples);
  ASSERT_EQ(truth.band[sample], BandClass::robust_lit);
  for (QueryKind query :
       {QueryKind::stack, QueryKind::depth, QueryKind::stackless, QueryKind::hybrid})
    EXPECT_EQ(run(h.c, h.samples, query).shadowed[sample], 0);

  // A random scene (blockers, samples on shadow images) at 2^-60 and 2^60.
  for (const int k : {-60, 60}) {
    const auto r = testing::scaled_by_power_of_two(
        testing::make_random_case(31, 8, 300, 0.75f, 600,
                                  testing::point_light({1.5f, 10.0f, 0.75f})),
        k);
    const HardShadowTruth scaled_truth = exact_hard_shadow_oracle(r.c, r.samples);
    for (QueryKind query :
         {QueryKind::stack, QueryKind::depth, QueryKind::stackless, QueryKind::hybrid}) {
      const HardShadowComparison comparison =
          compare_hard_shadows(run(r.c, r.samples, query).shadowed, scaled_truth);
      EXPECT_EQ(comparison.leaks + comparison.false_shadows, 0u)
          << "2^" << k << ": " << comparison.reason;
    }
  }
}

// fuzz_watertight-d28deb68f09fbe73: a shadow ray exactly through an edge E shared by two coplanar
// triangles, on a line that edges of other triangles continue. A point on an edge plane goes to
// the negative child only. The build filed a triangle that touches an edge plane from its
// positive side (two vertices on the line) under the positive child, so once a neighbour on E's
// line was inserted on each side before them (here after a triangle D whose plane parts the
// paths), each of E's triangles sat in the positive child of the other side's neighbour, out of
// the ray's reach: a leak on a robustly shadowed sample. Such triangles are filed under the
// intersection child now (triangle_location).
TEST(PsvSemantics, NoLeakThroughASharedEdgeOnALineThatOtherEdgesContinue) {
  const glm::vec3 light(0.25f, 6.0f, 0.375f);
  auto h = testing::make_hand_built_case(testing::point_light(light));
  h.c.triangles.clear();
  h.ground = h.add_triangle({-256, -8, -256}, {256, -8, -256}, {0, -8, 256}, testing::ground_mesh);
  // In the plane y = 2, E from (0, 0) to (1, 0) in (x, z); each triangle's first edge is the one
  // on the line z = 0 (its first plane in the tree).
  const auto at = [](float x, float z) { return glm::vec3(x, 2.0f, z); };
  h.add_triangle(at(-11.5f, 10.75f), at(12.5f, -9.25f),
                 at(30.0f, 20.0f));                       // D: 1.25 x + 1.5 z = 1.75
  h.add_triangle(at(1, 0), at(2, 0), at(2, -1));          // across D's line, below
  h.add_triangle(at(-1, 0), at(0, 0), at(-0.5f, 0.25f));  // beside D, above
  h.add_triangle(at(0, 0), at(1, 0), at(0.5f, 1));        // E's, across D's line
  h.add_triangle(at(1, 0), at(0, 0), at(0.5f, -1));       // E's, beside D
  // The ground points of crossings X, at L + 3.5 (X - L) (exact): through E, and through the
  // interiors of the others (so that each reaches a sample and stays in the tree).
  const std::size_t through_e = h.add_ground_sample({1.125f, -8.0f, -0.9375f});
  const std::vector<std::size_t> samples = {
      through_e, h.add_ground_sample({34.375f, -8.0f, 23.5625f}),
      h.add_ground_sample({5.5f, -8.0f, -1.8125f}), h.add_ground_sample({-2.375f, -8.0f, -0.5f})};
  const HardShadowTruth truth = exact_hard_shadow_oracle(h.c, h.samples);
  for (const std::size_t s : samples) ASSERT_EQ(truth.band[s], BandClass::robust_shadowed) << s;
  // The seeds' shuffles try many insertion orders: 14 of these 400 seeds leaked before.
  for (std::uint64_t seed = 1; seed <= 400; ++seed)
    for (QueryKind query :
         {QueryKind::stack, QueryKind::depth, QueryKind::stackless, QueryKind::hybrid}) {
      const PsvResult r = run(h.c, h.samples, query, 12, seed);
      ASSERT_EQ(counter(r, "triangles_inserted"), 5u);
      for (const std::size_t s : samples)
        EXPECT_EQ(r.shadowed[s], 1)
            << "sample " << s << ", seed " << seed << ", query " << int(query);
    }
}

}  // namespace
}  // namespace shadowcts::psv
