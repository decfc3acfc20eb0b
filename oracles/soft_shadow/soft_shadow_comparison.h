#pragma once
// Diffs an algorithm's visible fractions against the soft-shadow ground truth: error statistics
// and a verdict against the error budget the algorithm's variant declares.
//
// Per compared sample e = f_alg - f_truth. A robust sample fails when
//   |e| > budget.per_sample + truth.band_sensitivity + truth.error_bound
// (the algorithm's own budget, what the band allows, what the oracle itself is unsure of); the run
// fails when any robust sample fails, when the mean of the errors beyond the band (per compared
// sample max(0, |e| - band_sensitivity - error_bound): what no move of the sample within the band
// explains) exceeds the mean allowance (below), or when an output is NaN or outside [0, 1].
// Ambiguous samples never fail on their own, and count in the mean only with what their band
// cannot explain: a sample on a contact edge, whose truth jumps from 0 to 1 within the band,
// counts 0 whatever the answer.
//
// A declared mean budget is twice the mean error a faithful algorithm is expected to make
// (docs/soft-shadow-budgets.md), and its error beyond the band is at most b = budget.per_sample on
// every sample, so over M samples their mean exceeds budget.mean / 2 + t with probability at most
// exp(-2 M t^2 / b^2) (Hoeffding). The allowance is the larger of budget.mean and that bound at
// probability statistical_verdict_failure_probability: the budget itself once M is large (about
// 4,000 samples for softtile:grid16), and no verdict on a mean of a handful of samples.
#include <cstdint>
#include <string>
#include <vector>

#include "shadowcts/algorithm.h"
#include "shadowcts/soft_shadow_oracle.h"
#include "shadowcts/verdict.h"

namespace shadowcts {

struct SoftShadowComparison {
  std::uint64_t compared = 0;           // regular samples
  std::uint64_t robust = 0;             // of them, robust in the band
  std::uint64_t ambiguous = 0;          // compared - robust
  double mean_abs_error = 0.0;          // the figure reported
  double unexplained_mean_error = 0.0;  // mean of the errors beyond the band: the one judged
  double mean_allowance = 0.0;          // what unexplained_mean_error may reach (above)
  double rms_error = 0.0;
  double p99_abs_error = 0.0;  // 99th percentile of |e| (nearest rank)
  double max_abs_error = 0.0;
  double mean_signed_error = 0.0;     // bias: > 0 means too bright
  std::uint64_t umbra_leaks = 0;      // f_truth == 0 and f_alg > 0.5
  std::uint64_t lit_occlusions = 0;   // f_truth == 1 and f_alg < 0.5
  std::uint64_t over_budget = 0;      // robust samples over their allowance
  std::uint64_t invalid_outputs = 0;  // NaN or outside [0, 1] on compared samples
  std::int64_t worst_sample = -1;     // index of the largest |e| (-1: none compared)
  Verdict verdict = Verdict::pass;    // pass or fail
  std::string reason;                 // one line explaining the verdict
};

// `visible_fraction` has one entry per view sample (AlgorithmOutput::visible_fraction); samples the
// truth does not compare are ignored. Throws std::invalid_argument when the sizes differ.
SoftShadowComparison compare_soft_shadows(const std::vector<float>& visible_fraction,
                                          const SoftShadowTruth& truth,
                                          const SoftErrorBudget& budget);

}  // namespace shadowcts
