// The Embree peer algorithm agrees with the exact oracle on every robust sample.
#include "reference/embree/hard_shadow_embree.h"

#include <cmath>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include "hand_built_case.h"
#include "shadowcts/hard_shadow_oracle.h"

namespace shadowcts {
namespace {

TEST(EmbreeHardShadow, DescribesItself) {
  const auto algorithm = make_embree_hard_shadow();
  const AlgorithmInfo& info = algorithm->info();
  EXPECT_EQ(info.id, "embree");
  EXPECT_EQ(info.backend, "embree");
  EXPECT_EQ(info.variants, std::vector<std::string>{"robust"});
  EXPECT_TRUE(info.capabilities.point_light);
  EXPECT_TRUE(info.capabilities.directional_light);
}

TEST(EmbreeHardShadow, AgreesWithTheExactOracleOnRobustSamples) {
  for (const ShadowLight& light : {testing::point_light({1.5f, 10.0f, 0.75f}),
                                   testing::directional_light({0.25f, 1.0f, -0.375f})}) {
    const auto h = testing::make_random_case(21, 8, 1500, 0.75f, 3000, light,
                                             /*vertex_images=*/false);
    const HardShadowTruth truth = exact_hard_shadow_oracle(h.c, h.samples);
    const AlgorithmOutput output = make_embree_hard_shadow()->run(h.c, h.samples, "robust");
    std::size_t robust = 0;
    for (std::size_t i = 0; i < h.samples.samples.size(); ++i) {
      if (truth.band[i] == BandClass::ambiguous) continue;
      ++robust;
      EXPECT_EQ(output.shadowed[i], truth.shadowed[i]) << "robust sample " << i;
    }
    EXPECT_GT(robust, h.samples.samples.size() / 2);
    ASSERT_EQ(output.counters.size(), 1u);
    EXPECT_EQ(output.counters[0].first, "rays");
    EXPECT_EQ(output.counters[0].second, h.samples.samples.size());
  }
}

TEST(EmbreeHardShadow, ClosedFanDoesNotLeakAndReceiverIsIgnored) {
  auto h = testing::make_hand_built_case(testing::point_light({0.5f, 8, 0.5f}));
  testing::add_pyramid_fan(h);
  const std::uint32_t receiver = h.add_triangle({-1, 1, -1}, {1, 1, -1}, {0, 1, 1});
  const std::size_t through_edge = h.add_ground_sample({0.5f, 0, 0.5f});
  const std::size_t on_receiver = h.add_sample({0, 1, 0}, receiver);
  h.c.light->position = {0.5f, 8, 0.5f};
  const AlgorithmOutput output = make_embree_hard_shadow()->run(h.c, h.samples, "robust");
  EXPECT_EQ(output.shadowed[through_edge], 1);
  // Above the receiver the pyramid still blocks (0,1,0) -> (0.5, 8, 0.5); without the pyramid
  // the receiver alone must not.
  EXPECT_EQ(output.shadowed[on_receiver], 1);
  auto alone = testing::make_hand_built_case(testing::point_light({0.5f, 8, 0.5f}));
  const std::uint32_t only = alone.add_triangle({-1, 1, -1}, {1, 1, -1}, {0, 1, 1});
  const std::size_t i = alone.add_sample({0, 1, 0}, only);
  EXPECT_EQ(make_embree_hard_shadow()->run(alone.c, alone.samples, "robust").shadowed[i], 0);
}

// The case and its samples with every position multiplied by 2^k (exact in float away from
// denormals); directions stay.
testing::HandBuiltCase scaled(testing::HandBuiltCase h, int k) {
  h = testing::scaled_by_power_of_two(std::move(h), k);
  h.c.camera.near_plane = std::ldexp(h.c.camera.near_plane, k);
  h.c.camera.far_plane = std::ldexp(h.c.camera.far_plane, k);
  return h;
}

// Robust samples where Embree disagrees with the exact oracle.
std::size_t robust_mismatches(const testing::HandBuiltCase& h) {
  const HardShadowTruth truth = exact_hard_shadow_oracle(h.c, h.samples);
  const AlgorithmOutput output = make_embree_hard_shadow()->run(h.c, h.samples, "robust");
  std::size_t mismatches = 0, robust = 0;
  for (std::size_t i = 0; i < h.samples.samples.size(); ++i) {
    if (truth.band[i] == BandClass::ambiguous) continue;
    ++robust;
    mismatches += output.shadowed[i] != truth.shadowed[i];
  }
  EXPECT_GT(robust, 0u);
  return mismatches;
}

// Embree's float32 ray/triangle products of three coordinates hold the answer only for case
// scales S in [2^-34, 2^39] (hard_shadow_embree.h derives the bound); outside it the algorithm
// declines, naming the range, instead of answering. At both ends of the range it still agrees
// with the exact oracle.
TEST(EmbreeHardShadow, DeclaresItsFloat32RangeOfScales) {
  const auto embree = make_embree_hard_shadow();
  for (const ShadowLight& light : {testing::point_light({1.5f, 10.0f, 0.75f}),
                                   testing::directional_light({0.25f, 1.0f, -0.375f})}) {
    const auto h = testing::make_random_case(7, 8, 300, 0.75f, 600, light,
                                             /*vertex_images=*/false);
    const double s = h.c.scale();
    // The extreme powers of two that keep S inside [2^-34, 2^39], and one step beyond each.
    const int lowest = int(std::ceil(embree_min_scale_exponent - std::log2(s)));
    const int highest = int(std::floor(embree_max_scale_exponent - std::log2(s)));
    for (const int k : {lowest, highest}) {
      const auto inside = scaled(h, k);
      ASSERT_EQ(embree->unsupported_reason(inside.c, inside.samples, "robust"), std::nullopt)
          << "2^" << k;
      EXPECT_EQ(robust_mismatches(inside), 0u) << "scaled by 2^" << k;
    }
    for (const int k : {lowest - 1, highest + 1}) {
      const auto outside = scaled(h, k);
      const auto why = embree->unsupported_reason(outside.c, outside.samples, "robust");
      ASSERT_TRUE(why.has_value()) << "2^" << k;
      EXPECT_NE(why->find("float32 range 2^-34 <= S <= 2^39"), std::string::npos) << *why;
    }
  }
  // A directional light given as a tiny vector shrinks the edge tests' products as a tiny scene
  // would.
  auto tiny_direction =
      testing::make_random_case(7, 8, 30, 0.75f, 60, testing::directional_light({0, 0x1p-110f, 0}));
  const auto why = embree->unsupported_reason(tiny_direction.c, tiny_direction.samples, "robust");
  ASSERT_TRUE(why.has_value());
  EXPECT_NE(why->find("light direction"), std::string::npos) << *why;
}

// Found by fuzz_degenerate (crash-4bdd3f65...): a scene scaled by about 2^-44 where Embree's
// products of ~2^-130 are float32 denormals and a robust-shadowed sample leaked. The same two
// triangles scaled up by 2^47 are answered right; at their own scale Embree declines.
TEST(EmbreeHardShadow, FuzzSceneAtTwoToTheMinus44IsDeclinedNotLeaked) {
  auto h =
      testing::make_hand_built_case(testing::point_light({-0x1.4cp-45f, 0x1.54p-43f, -0x1.1p-47f}));
  h.c.triangles.clear();
  h.ground = h.add_triangle({-0x1p-44f, -0x1p-44f, -0x1p-44f}, {0x1p-44f, -0x1p-44f, -0x1p-44f},
                            {0.0f, -0x1p-44f, 0x1p-44f}, testing::ground_mesh);
  h.add_triangle({-0x1.ep-47f, -0x1.28p-46f, 0x1.28p-46f},
                 {-0x1.f8p-45f, -0x1.acp-45f, -0x1.e4p-45f},
                 {-0x1.6p-45f, -0x1.bp-47f, 0x1.4cp-45f});
  h.c.camera.position = {-0x1.8d9feap-46f, 0x1.3f59acp-44f, -0x1.45c3cap-48f};
  h.c.camera.target = {0.0f, -0x1.8p-44f, 0.0f};
  h.c.camera.near_plane = 0x1p-60f;
  h.c.camera.far_plane = 0x1p-30f;
  const std::size_t sample = h.add_ground_sample({-0x1p-44f, -0x1.8p-44f, -0x1p-44f});

  const HardShadowTruth truth = exact_hard_shadow_oracle(h.c, h.samples);
  ASSERT_EQ(truth.band[sample], BandClass::robust_shadowed);
  const auto embree = make_embree_hard_shadow();
  const auto why = embree->unsupported_reason(h.c, h.samples, "robust");
  ASSERT_TRUE(why.has_value());
  EXPECT_NE(why->find("denormals"), std::string::npos) << *why;

  const auto up = scaled(h, 47);
  ASSERT_EQ(embree->unsupported_reason(up.c, up.samples, "robust"), std::nullopt);
  EXPECT_EQ(exact_hard_shadow_oracle(up.c, up.samples).band[sample], BandClass::robust_shadowed);
  EXPECT_EQ(embree->run(up.c, up.samples, "robust").shadowed[sample], 1);
}

// A documented limit of the peer (docs/specification.md), kept failing on purpose: Embree's
// float edge functions agree in sign across a shared edge, but a ray exactly through a vertex
// that several triangles share meets only near-zero rounded values, which can all exclude it.
// Found by fuzz_watertight (a closed fan of three triangles, dyadic vertices, the sample beyond
// the apex seen from the light); 1.7 % of such rays through fan apices miss. When this test
// fails, Embree has become watertight at vertices: update the specification and fuzz_watertight.
TEST(EmbreeHardShadow, ARayThroughASharedVertexCanMissEveryTriangleAroundIt) {
  auto h = testing::make_hand_built_case(testing::point_light({8.0f, 21.0f, 18.0f}));
  const glm::vec3 apex{6.625f, -7.25f, 2.125f};
  const glm::vec3 rim[3] = {{7.4375f, -7.5625f, 2.125f},
                            {5.9375f, -7.5f, 3.30664062f},
                            {5.90625f, -7.625f, 0.889648438f}};
  for (int i = 0; i < 3; ++i) h.add_triangle(apex, rim[i], rim[(i + 1) % 3]);
  // Beyond the apex: p = apex + 3.75 (apex - L), exact in float, so the segment to L passes
  // exactly through the apex, inside the fan as seen from the light. Its receiver is a floor
  // through p (the fan lies on the light's side of its plane, as the receiver half-space rule
  // needs; the hand-built ground at y = 0 would put the fan beyond it).
  const float floor_y = -113.1875f;
  const std::uint32_t floor =
      h.add_triangle({-200.0f, floor_y, -200.0f}, {200.0f, floor_y, -200.0f},
                     {0.0f, floor_y, 200.0f}, testing::ground_mesh);
  const std::size_t through_apex = h.add_sample({1.46875f, floor_y, -57.40625f}, floor);
  const HardShadowTruth truth = exact_hard_shadow_oracle(h.c, h.samples);
  ASSERT_EQ(truth.band[through_apex], BandClass::robust_shadowed);
  EXPECT_EQ(make_embree_hard_shadow()->run(h.c, h.samples, "robust").shadowed[through_apex], 0);
}

}  // namespace
}  // namespace shadowcts
