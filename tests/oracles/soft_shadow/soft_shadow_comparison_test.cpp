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
  // 10,000 robust samples: the allowance is the budget itself.
  const std::vector<float> output(10000, 0.52f);
  const SoftShadowComparison r =
      compare_soft_shadows(output, make_truth(std::vector<double>(10000, 0.5)), {0.1, 0.01});
  EXPECT_EQ(r.mean_allowance, 0.01);
  EXPECT_EQ(r.verdict, Verdict::fail);
  EXPECT_NE(r.reason.find("mean"), std::string::npos) << r.reason;
}

TEST(SoftShadowComparison, TheMeanCountsOnlyTheErrorTheBandDoesNotExplain) {
  // A sample on a contact edge may be answered 1 where the truth is 0 (its band sensitivity is 1):
  // in the reported mean, not in the judged one.
  SoftShadowTruth truth = make_truth(std::vector<double>(10000, 0.5));
  std::vector<float> output(10000, 0.5f);
  for (std::size_t i = 0; i < 500; ++i) {
    truth.visible_fraction[i] = 0.0;
    truth.band_sensitivity[i] = 1.0;
    truth.robust[i] = 0;
    output[i] = 1.0f;
  }
  SoftShadowComparison r = compare_soft_shadows(output, truth, {0.1, 0.01});
  EXPECT_NEAR(r.mean_abs_error, 0.05, 1e-12);
  EXPECT_EQ(r.unexplained_mean_error, 0.0);
  EXPECT_EQ(r.verdict, Verdict::pass) << r.reason;
  // Ambiguous samples whose band explains only part of the error count with the rest: 0.05 - 0.02
  // on 5 % of the samples is a mean of 0.0015 ...
  for (std::size_t i = 0; i < 500; ++i) {
    truth.visible_fraction[i] = 0.45;
    truth.band_sensitivity[i] = 0.02;
    output[i] = 0.5f;
  }
  r = compare_soft_shadows(output, truth, {0.1, 0.01});
  EXPECT_NEAR(r.unexplained_mean_error, 0.0015, 1e-8);
  EXPECT_EQ(r.verdict, Verdict::pass) << r.reason;
  // ... and 0.5 - 0.02 on them is 0.024, over the budget.
  for (std::size_t i = 0; i < 500; ++i) output[i] = 0.95f;
  r = compare_soft_shadows(output, truth, {0.1, 0.01});
  EXPECT_NEAR(r.unexplained_mean_error, 0.024, 1e-8);
  EXPECT_EQ(r.verdict, Verdict::fail) << r.reason;
  EXPECT_EQ(r.over_budget, 0u);  // failed by the mean alone
}

TEST(SoftShadowComparison, TheMeanOfAFewSamplesIsJudgedWithItsSamplingSpread) {
  // grid16's budget; every robust sample in a penumbra, each within its per-sample budget, 0.05
  // off: three times the mean budget, which a faithful algorithm reaches on a few samples by
  // chance and on many only by a fault.
  const SoftErrorBudget grid16{0.1538, 0.0157};
  const auto judge = [&](std::size_t m) {
    return compare_soft_shadows(std::vector<float>(m, 0.55f),
                                make_truth(std::vector<double>(m, 0.5)), grid16);
  };
  const SoftShadowComparison few = judge(20);
  const double spread =
      0.1538 * std::sqrt(std::log(1.0 / statistical_verdict_failure_probability) / 40.0);
  EXPECT_NEAR(few.mean_allowance, 0.0157 / 2 + spread, 1e-12);
  EXPECT_EQ(few.verdict, Verdict::pass) << few.reason;
  const SoftShadowComparison many = judge(5000);
  EXPECT_EQ(many.mean_allowance, 0.0157);
  EXPECT_EQ(many.verdict, Verdict::fail) << many.reason;
  // Between them the allowance falls as 1 / sqrt(M) to the budget.
  EXPECT_GT(judge(100).mean_allowance, judge(400).mean_allowance);
  EXPECT_EQ(judge(100).verdict, Verdict::pass);
  EXPECT_EQ(judge(1000).verdict, Verdict::fail) << judge(1000).reason;
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
