// The soft-shadow comparison: statistics, the per-sample and mean budgets, the band allowance,
// leaks and lit-region occlusions, invalid outputs.
#include <cmath>

#include <gtest/gtest.h>

#include "oracles/soft_shadow/soft_shadow_comparison.h"

namespace shadowcts {
namespace {

SoftShadowTruth make_truth(const std::vector<double>& fractions) {
  SoftShadowTruth truth;
  truth.exact = true;
  truth.visible_fraction = fractions;
  truth.error_bound.assign(fractions.size(), 0.0);
  truth.band_sensitivity.assign(fractions.size(), 0.0);
  truth.robust.assign(fractions.size(), 1);
  truth.compared.assign(fractions.size(), 1);
  return truth;
}

TEST(SoftShadowComparison, StatisticsOfTheErrors) {
  std::vector<double> exact(100, 0.5);
  std::vector<float> output(100, 0.5f);
  output[0] = 0.6f;   // +0.1
  output[1] = 0.45f;  // -0.05
  const SoftShadowComparison r = compare_soft_shadows(output, make_truth(exact), {0.2, 0.01});
  EXPECT_EQ(r.compared, 100u);
  EXPECT_NEAR(r.max_abs_error, 0.1, 1e-7);
  EXPECT_EQ(r.worst_sample, 0);
  EXPECT_NEAR(r.mean_abs_error, 0.15 / 100, 1e-8);
  EXPECT_NEAR(r.mean_signed_error, 0.05 / 100, 1e-8);
  EXPECT_NEAR(r.rms_error, std::sqrt((0.01 + 0.0025) / 100), 1e-7);
  EXPECT_NEAR(r.p99_abs_error, 0.05, 1e-7);  // the 99th of 100 sorted magnitudes
  EXPECT_EQ(r.verdict, Verdict::pass) << r.reason;
}

TEST(SoftShadowComparison, PerSampleBudgetFailsOnlyRobustSamples) {
  SoftShadowTruth truth = make_truth({0.0, 1.0, 0.5, 0.5});
  const std::vector<float> output{0.7f, 0.2f, 0.5f, 0.5f};  // a leak and an occlusion
  SoftShadowComparison r = compare_soft_shadows(output, truth, {0.5, 1.0});
  EXPECT_EQ(r.umbra_leaks, 1u);
  EXPECT_EQ(r.lit_occlusions, 1u);
  EXPECT_EQ(r.verdict, Verdict::fail);
  EXPECT_EQ(r.over_budget, 2u);
  // Ambiguous samples never fail on their own ...
  truth.robust = {0, 0, 1, 1};
  r = compare_soft_shadows(output, truth, {0.5, 1.0});
  EXPECT_EQ(r.verdict, Verdict::pass) << r.reason;
  EXPECT_EQ(r.ambiguous, 2u);
  // ... and a robust sample's allowance includes its band sensitivity and the truth's bound.
  truth.robust = {1, 1, 1, 1};
  truth.band_sensitivity = {0.1, 0.0, 0.0, 0.0};
  truth.error_bound = {0.1, 0.31, 0.0, 0.0};
  r = compare_soft_shadows(output, truth, {0.5, 1.0});
  EXPECT_EQ(r.verdict, Verdict::pass) << r.reason;
}

TEST(SoftShadowComparison, MeanBudget) {
  const std::vector<float> output(10, 0.52f);
  const SoftShadowComparison r =
      compare_soft_shadows(output, make_truth(std::vector<double>(10, 0.5)), {0.1, 0.01});
  EXPECT_EQ(r.verdict, Verdict::fail);
  EXPECT_NE(r.reason.find("mean"), std::string::npos) << r.reason;
}

TEST(SoftShadowComparison, NotComparedSamplesAndInvalidOutputs) {
  SoftShadowTruth truth = make_truth({0.5, 0.5, 0.5});
  truth.compared = {1, 0, 1};
  truth.robust = {1, 0, 1};
  SoftShadowComparison r = compare_soft_shadows({0.5f, 100.0f, 0.5f}, truth, {0.01, 0.01});
  EXPECT_EQ(r.compared, 2u);
  EXPECT_EQ(r.verdict, Verdict::pass) << r.reason;
  r = compare_soft_shadows({0.5f, 0.5f, std::nanf("")}, truth, {0.01, 0.01});
  EXPECT_EQ(r.invalid_outputs, 1u);
  EXPECT_EQ(r.verdict, Verdict::fail);
  EXPECT_THROW(compare_soft_shadows({0.5f}, truth, {0.01, 0.01}), std::invalid_argument);
}

}  // namespace
}  // namespace shadowcts
