#include "shadowcts/hard_shadow_comparison.h"

#include <gtest/gtest.h>

namespace shadowcts {
namespace {

struct TruthBuilder {
  HardShadowTruth truth;
  void add(bool shadowed, BandClass band, std::int8_t robust_exponent) {
    truth.shadowed.push_back(shadowed);
    truth.band.push_back(band);
    truth.robust_exponent.push_back(robust_exponent);
  }
};

TEST(HardShadowComparison, CountsLeaksFalseShadowsAndAmbiguousSeparately) {
  TruthBuilder b;
  b.add(true, BandClass::robust_shadowed, -10);  // 0: answered lit -> leak
  b.add(false, BandClass::robust_lit, -10);      // 1: answered shadowed -> false shadow
  b.add(true, BandClass::robust_shadowed, -10);  // 2: right
  b.add(false, BandClass::ambiguous, -20);       // 3: ambiguous, answered differently
  b.add(false, BandClass::not_compared, -10);    // 4: sky: ignored whatever the answer
  const std::vector<std::uint8_t> answer = {0, 1, 1, 1, 1};
  const HardShadowComparison r = compare_hard_shadows(answer, b.truth);
  EXPECT_EQ(r.compared, 4u);
  EXPECT_EQ(r.robust, 3u);
  EXPECT_EQ(r.ambiguous, 1u);
  EXPECT_EQ(r.leaks, 1u);
  EXPECT_EQ(r.false_shadows, 1u);
  EXPECT_EQ(r.ambiguous_disagreements, 1u);
  EXPECT_EQ(r.verdict, Verdict::fail);
}

TEST(HardShadowComparison, MismatchCurveFollowsRobustExponents) {
  TruthBuilder b;
  b.add(true, BandClass::ambiguous, -20);  // wrong; robust only up to 2^-20
  b.add(false, BandClass::ambiguous, ambiguous_at_every_exponent);  // wrong; never robust
  b.add(true, BandClass::robust_shadowed, -12);                     // right
  const HardShadowComparison r = compare_hard_shadows({0, 1, 1}, b.truth);
  ASSERT_EQ(r.mismatch_curve.size(), std::size_t(band_max_exponent - band_min_exponent + 1));
  for (const auto& [e, mismatches] : r.mismatch_curve) EXPECT_EQ(mismatches, e <= -20 ? 1u : 0u);
  // Non-increasing in eps_rel.
  for (std::size_t i = 1; i < r.mismatch_curve.size(); ++i)
    EXPECT_LE(r.mismatch_curve[i].second, r.mismatch_curve[i - 1].second);
  EXPECT_EQ(r.verdict, Verdict::pass);  // only 2 ambiguous disagreements: below the minimum
}

TEST(HardShadowComparison, SystematicAmbiguousBiasIsAQualityWarning) {
  // k of 58 ambiguous samples differ. P(X >= 41) = 0.0011 and P(X >= 42) = 0.00043 for a coin:
  // 41 is chance, 42 a bias.
  const auto compare = [](std::size_t differing) {
    TruthBuilder b;
    std::vector<std::uint8_t> answer;
    for (std::size_t i = 0; i < 58; ++i) {
      b.add(true, BandClass::ambiguous, -18);
      answer.push_back(i >= differing);
    }
    b.add(false, BandClass::robust_lit, -10);
    answer.push_back(0);
    return compare_hard_shadows(answer, b.truth);
  };
  EXPECT_EQ(compare(31).verdict, Verdict::pass);
  EXPECT_EQ(compare(41).verdict, Verdict::pass);
  const HardShadowComparison r = compare(42);
  EXPECT_EQ(r.ambiguous_disagreements, 42u);
  EXPECT_EQ(r.verdict, Verdict::quality_warning) << r.reason;
  EXPECT_EQ(compare(58).verdict, Verdict::quality_warning);
}

TEST(HardShadowComparison, RejectsOutputOfTheWrongSize) {
  TruthBuilder b;
  b.add(true, BandClass::robust_shadowed, -10);
  EXPECT_THROW(compare_hard_shadows({1, 0}, b.truth), std::invalid_argument);
}

}  // namespace
}  // namespace shadowcts
