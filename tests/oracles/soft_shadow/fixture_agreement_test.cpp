// The exact soft-shadow oracle against the sampled one on the soft-shadow fixtures: every compared
// sample within the sampled oracle's stated bound, and far closer on average (stratification);
// both call the same samples ambiguous.
// Pixels are subsampled to keep CI time modest.
#include <chrono>
#include <cmath>

#include <gtest/gtest.h>

#include "shadowcts/fixtures.h"
#include "shadowcts/soft_shadow_oracle.h"
#include "tests/oracles/soft_shadow/soft_case.h"
#include "tests/test_name.h"

namespace shadowcts {
namespace {

struct SoftFixture {
  const char* name;
  std::size_t stride;  // every stride-th regular sample is compared
};

class SoftFixtureAgreement : public ::testing::TestWithParam<SoftFixture> {};

TEST_P(SoftFixtureAgreement, ExactWithinSampledBound) {
  Case c = make_fixture(GetParam().name);
  ASSERT_TRUE(c.light && c.light->kind == ShadowLightKind::sun_disk);
  const ViewSamples samples =
      testing::every_nth_regular(generate_view_samples(c), GetParam().stride);
  const auto start = std::chrono::steady_clock::now();
  const SoftShadowTruth exact = exact_soft_shadow_oracle(c, samples);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const SoftShadowTruth sampled = sampled_soft_shadow_oracle(c, samples, 1024);

  std::size_t compared = 0, robust = 0, penumbra = 0;
  double sum_difference = 0.0, worst = 0.0, bound = 0.0;
  for (std::size_t i = 0; i < samples.samples.size(); ++i) {
    ASSERT_EQ(exact.compared[i], sampled.compared[i]);
    if (!exact.compared[i]) continue;
    ++compared;
    robust += exact.robust[i];
    // Both oracles classify by the same band sensitivity bound: ambiguous samples are the same.
    EXPECT_EQ(sampled.band_sensitivity[i], exact.band_sensitivity[i]) << "sample " << i;
    EXPECT_EQ(sampled.robust[i], exact.robust[i]) << "sample " << i;
    penumbra += exact.visible_fraction[i] > 0.0 && exact.visible_fraction[i] < 1.0;
    const double difference = std::fabs(exact.visible_fraction[i] - sampled.visible_fraction[i]);
    EXPECT_LE(difference, sampled.error_bound[i])
        << "sample " << i << ": exact " << exact.visible_fraction[i] << ", sampled "
        << sampled.visible_fraction[i];
    sum_difference += difference;
    bound = sampled.error_bound[i];
    worst = std::max(worst, difference);
  }
  ASSERT_GT(compared, 100u);
  // Some samples are ambiguous (near a caster), or the classification is not tested.
  EXPECT_LT(robust, compared);
  EXPECT_GT(robust, compared / 2);
  // The fixture must exercise the penumbra, or the comparison tests little.
  EXPECT_GT(penumbra, compared / 20);
  // Stratified sampling: the mean difference is a small fraction of the worst-case bound.
  EXPECT_LT(sum_difference / double(compared), 0.01);
  std::printf(
      "%s: %zu samples (%zu robust, %zu penumbra), exact oracle %.3f ms/sample, "
      "%llu candidates, mean |exact - sampled| %.5f, max %.4f (bound %.4f)\n",
      GetParam().name, compared, robust, penumbra, 1e3 * seconds / double(compared),
      static_cast<unsigned long long>(exact.candidate_triangles), sum_difference / double(compared),
      worst, bound);
}

INSTANTIATE_TEST_SUITE_P(SoftFixtures, SoftFixtureAgreement,
                         ::testing::Values(SoftFixture{"foliage.10k", 13}),
                         [](const auto& test_info) {
                           return test_support::test_name(test_info.param.name);
                         });

}  // namespace
}  // namespace shadowcts
