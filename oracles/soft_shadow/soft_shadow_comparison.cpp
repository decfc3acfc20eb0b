#include "oracles/soft_shadow/soft_shadow_comparison.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace shadowcts {
namespace {

std::string format(const char* pattern, double value) {
  char text[64];
  std::snprintf(text, sizeof text, pattern, value);
  return text;
}

}  // namespace

SoftShadowComparison compare_soft_shadows(const std::vector<float>& visible_fraction,
                                          const SoftShadowTruth& truth,
                                          const SoftErrorBudget& budget) {
  const std::size_t n = truth.visible_fraction.size();
  if (visible_fraction.size() != n || truth.compared.size() != n || truth.robust.size() != n ||
      truth.error_bound.size() != n || truth.band_sensitivity.size() != n)
    throw std::invalid_argument("compare_soft_shadows: " + std::to_string(visible_fraction.size()) +
                                " visible fractions for " + std::to_string(n) + " truth samples");
  SoftShadowComparison result;
  std::vector<double> magnitudes;
  double sum_abs = 0.0, sum_squared = 0.0, sum_signed = 0.0;
  double worst_excess = 0.0;
  double sum_unexplained = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!truth.compared[i]) continue;
    ++result.compared;
    const double f_truth = truth.visible_fraction[i];
    const double f = double(visible_fraction[i]);
    if (!(f >= 0.0 && f <= 1.0)) {  // NaN fails this too
      ++result.invalid_outputs;
      continue;
    }
    const double e = f - f_truth;
    const double magnitude = std::fabs(e);
    magnitudes.push_back(magnitude);
    sum_abs += magnitude;
    sum_squared += e * e;
    sum_signed += e;
    if (result.worst_sample < 0 || magnitude > result.max_abs_error) {
      result.max_abs_error = magnitude;
      result.worst_sample = std::int64_t(i);
    }
    if (f_truth == 0.0 && f > 0.5) ++result.umbra_leaks;
    if (f_truth == 1.0 && f < 0.5) ++result.lit_occlusions;
    // What no move of the sample within the band, and no error of the oracle, explains.
    sum_unexplained += std::max(0.0, magnitude - truth.band_sensitivity[i] - truth.error_bound[i]);
    if (truth.robust[i]) {
      ++result.robust;
      const double allowance = budget.per_sample + truth.band_sensitivity[i] + truth.error_bound[i];
      if (magnitude > allowance) {
        ++result.over_budget;
        worst_excess = std::max(worst_excess, magnitude - allowance);
      }
    }
  }
  result.ambiguous = result.compared - result.robust;
  const double valid = double(magnitudes.size());
  if (!magnitudes.empty()) {
    result.mean_abs_error = sum_abs / valid;
    result.rms_error = std::sqrt(sum_squared / valid);
    result.mean_signed_error = sum_signed / valid;
    // Nearest rank: the smallest value with at least 99 % of the samples at or below it.
    const auto rank = std::size_t(std::ceil(0.99 * valid)) - 1;
    std::nth_element(magnitudes.begin(), magnitudes.begin() + std::ptrdiff_t(rank),
                     magnitudes.end());
    result.p99_abs_error = magnitudes[rank];
    result.unexplained_mean_error = sum_unexplained / valid;
    const double b = std::min(1.0, budget.per_sample);
    const double sampling =
        b * std::sqrt(std::log(1.0 / statistical_verdict_failure_probability) / (2.0 * valid));
    result.mean_allowance = std::max(budget.mean, 0.5 * budget.mean + sampling);
  }

  std::string stats =
      std::to_string(result.compared) + " compared (" + std::to_string(result.robust) +
      " robust), mean |e| " + format("%.3g", result.mean_abs_error) + " (beyond the band " +
      format("%.3g", result.unexplained_mean_error) + ", allowed " +
      format("%.3g", result.mean_allowance) + "), p99 " + format("%.3g", result.p99_abs_error) +
      ", max " + format("%.3g", result.max_abs_error) + ", bias " +
      format("%+.3g", result.mean_signed_error);
  if (result.invalid_outputs > 0) {
    result.verdict = Verdict::fail;
    result.reason = std::to_string(result.invalid_outputs) +
                    " visible fractions are NaN or outside [0, 1]; " + stats;
  } else if (result.over_budget > 0) {
    result.verdict = Verdict::fail;
    result.reason = std::to_string(result.over_budget) +
                    " robust samples exceed the per-sample budget " +
                    format("%.3g", budget.per_sample) + " (worst by " +
                    format("%.3g", worst_excess) + "); " + stats;
  } else if (result.unexplained_mean_error > result.mean_allowance) {
    result.verdict = Verdict::fail;
    result.reason = "mean |e| beyond the band " + format("%.3g", result.unexplained_mean_error) +
                    " exceeds the mean budget " + format("%.3g", budget.mean) + " (allowed over " +
                    std::to_string(magnitudes.size()) +
                    " samples: " + format("%.3g", result.mean_allowance) + "); " + stats;
  } else {
    result.verdict = Verdict::pass;
    result.reason = "within budget (per sample " + format("%.3g", budget.per_sample) + ", mean " +
                    format("%.3g", budget.mean) + "); " + stats;
  }
  return result;
}

}  // namespace shadowcts
