// The brute-force reference gives the exact oracle's answer on every regular sample.
#include "reference/bruteforce/hard_shadow_bruteforce.h"

#include <gtest/gtest.h>

#include "hand_built_case.h"
#include "shadowcts/hard_shadow_oracle.h"

namespace shadowcts {
namespace {

TEST(BruteforceHardShadow, DescribesItself) {
  const auto algorithm = make_bruteforce_hard_shadow();
  const AlgorithmInfo& info = algorithm->info();
  EXPECT_EQ(info.id, "bruteforce");
  EXPECT_EQ(info.backend, "reference");
  EXPECT_EQ(info.variants, std::vector<std::string>{"exact"});
  EXPECT_EQ(info.capabilities.output, OutputKind::hard_shadow);
  EXPECT_TRUE(info.capabilities.point_light);
  EXPECT_TRUE(info.capabilities.directional_light);
  EXPECT_FALSE(info.capabilities.sun_disk);
  EXPECT_GT(info.capabilities.max_sample_triangle_pairs, 0u);
}

class BruteforceAgainstExactOracle : public ::testing::TestWithParam<int> {};

TEST_P(BruteforceAgainstExactOracle, SameAnswerOnEverySample) {
  const ShadowLight light = GetParam() % 2 == 0
                                ? testing::point_light({1.5f, 10.0f, 0.75f})
                                : testing::directional_light({0.25f, 1.0f, -0.375f});
  auto h = testing::make_random_case(100 + std::uint64_t(GetParam()), 8, 800, 0.75f, 1500, light);
  h.samples.samples[3].sample_class = SampleClass::sky;  // never shadowed in the output
  const HardShadowTruth truth = exact_hard_shadow_oracle(h.c, h.samples);
  const auto algorithm = make_bruteforce_hard_shadow();
  const AlgorithmOutput output = algorithm->run(h.c, h.samples, "exact");
  ASSERT_EQ(output.shadowed.size(), h.samples.samples.size());
  std::size_t shadowed = 0;
  for (std::size_t i = 0; i < output.shadowed.size(); ++i) {
    EXPECT_EQ(output.shadowed[i], truth.shadowed[i]) << "sample " << i;
    shadowed += output.shadowed[i];
  }
  EXPECT_EQ(output.shadowed[3], 0);
  EXPECT_GT(shadowed, output.shadowed.size() / 10);  // not a trivially lit case

  ASSERT_EQ(output.counters.size(), 2u);
  EXPECT_EQ(output.counters[0].first, "pair_tests");
  EXPECT_EQ(output.counters[1].first, "exact_predicate_calls");
  EXPECT_GT(output.counters[1].second, 0u);
  EXPECT_LE(output.counters[1].second, output.counters[0].second);
  // The counters are the same for any thread count.
  h.c.parameters.threads = 1;
  const AlgorithmOutput single = algorithm->run(h.c, h.samples, "exact");
  EXPECT_EQ(single.shadowed, output.shadowed);
  EXPECT_EQ(single.counters, output.counters);
}

INSTANTIATE_TEST_SUITE_P(RandomCases, BruteforceAgainstExactOracle, ::testing::Range(0, 4));

TEST(BruteforceHardShadow, SharedEdgesZeroAreaAndReceivers) {
  auto h = testing::make_hand_built_case(testing::point_light({0.5f, 8, 0.5f}));
  testing::add_pyramid_fan(h);
  h.add_triangle({-1, 1, 0}, {1, 1, 0}, {0, 1, 0});  // zero area, across the segment
  const std::size_t through_edge = h.add_ground_sample({0.5f, 0, 0.5f});
  const std::size_t on_receiver = h.add_sample({0.5f, 2.5f, 0.5f}, 3);  // on the fan's edge
  const AlgorithmOutput output = make_bruteforce_hard_shadow()->run(h.c, h.samples, "exact");
  EXPECT_EQ(output.shadowed[through_edge], 1);
  // The sample on the edge shared by triangles 2 and 3 (receiver 3) also lies on triangle 2, but
  // only in the receiver's plane, not strictly on the light's side of it (the receiver
  // half-space rule): the next face of the fan does not shadow it.
  EXPECT_EQ(output.shadowed[on_receiver], 0);
}

TEST(BruteforceHardShadow, RejectsUnknownVariants) {
  auto h = testing::make_hand_built_case(testing::point_light({0, 8, 0}));
  h.add_ground_sample({0, 0, 0});
  EXPECT_THROW(make_bruteforce_hard_shadow()->run(h.c, h.samples, "fast"), std::invalid_argument);
}

}  // namespace
}  // namespace shadowcts
