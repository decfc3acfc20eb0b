// The Embree peer algorithm agrees with the exact oracle on every robust sample.
#include "reference/embree/hard_shadow_embree.h"

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

}  // namespace
}  // namespace shadowcts
