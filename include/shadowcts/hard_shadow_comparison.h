#pragma once
// Diffs an algorithm's hard-shadow mask against the ground truth, band by band.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "shadowcts/hard_shadow_truth.h"
#include "shadowcts/verdict.h"

namespace shadowcts {

struct HardShadowComparison {
  std::uint64_t compared = 0;       // regular samples
  std::uint64_t robust = 0;         // robust at the run's eps_rel
  std::uint64_t ambiguous = 0;      // ambiguous at the run's eps_rel
  std::uint64_t leaks = 0;          // robust samples answered lit where the truth is shadowed
  std::uint64_t false_shadows = 0;  // robust samples answered shadowed where the truth is lit
  // Ambiguous samples whose answer differs from the exact answer at the unmoved sample.
  std::uint64_t ambiguous_disagreements = 0;
  // (e, robust mismatches at eps_rel = 2^e) for e = band_min_exponent ... band_max_exponent.
  // Non-increasing in e: a larger band makes fewer samples robust.
  std::vector<std::pair<int, std::uint64_t>> mismatch_curve;
  Verdict verdict = Verdict::pass;
  std::string reason;  // one line explaining the verdict
};

// QualityWarning: every robust sample is right, but more of the ambiguous samples disagree with
// the exact answer than chance explains. An implementation whose rounding is unbiased gets about
// half of them right or better; doing worse means a systematic bias at shadow boundaries (e.g.
// half-open edges), worth a look. "Worse" is a binomial test: the warning is given when k of n
// disagreements are at most quality_warning_probability likely for a coin (P(X >= k) with
// X ~ Binomial(n, 1/2)), so 41 of 58 is no warning and 42 of 58 is one.
inline constexpr double quality_warning_probability = 1e-3;

// `shadowed` has one entry per sample (1 = shadowed); samples the truth does not compare are
// ignored.
HardShadowComparison compare_hard_shadows(const std::vector<std::uint8_t>& shadowed,
                                          const HardShadowTruth& truth);

}  // namespace shadowcts
