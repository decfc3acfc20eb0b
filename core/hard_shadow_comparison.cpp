#include "shadowcts/hard_shadow_comparison.h"

#include <stdexcept>

#include <boost/math/distributions/binomial.hpp>

namespace shadowcts {
namespace {

// P(X >= k) for X ~ Binomial(n, 1/2): how likely k of n ambiguous disagreements are by chance.
double chance_of_at_least(std::uint64_t k, std::uint64_t n) {
  if (k == 0) return 1.0;
  const boost::math::binomial_distribution<double> coin(double(n), 0.5);
  return boost::math::cdf(boost::math::complement(coin, double(k - 1)));
}

}  // namespace

HardShadowComparison compare_hard_shadows(const std::vector<std::uint8_t>& shadowed,
                                          const HardShadowTruth& truth) {
  if (shadowed.size() != truth.shadowed.size())
    throw std::invalid_argument("algorithm output has " + std::to_string(shadowed.size()) +
                                " samples, the truth " + std::to_string(truth.shadowed.size()));
  HardShadowComparison r;
  constexpr int exponents = band_max_exponent - band_min_exponent + 1;
  std::vector<std::uint64_t> curve(exponents, 0);

  // The mismatch curve needs the robust exponents of the samples answered differently: those the
  // oracle left to compute on demand are computed now (in a copy: the truth stays as it is).
  std::vector<std::size_t> unknown;
  for (std::size_t i = 0; i < shadowed.size(); ++i)
    if (truth.band[i] != BandClass::not_compared &&
        (shadowed[i] != 0) != (truth.shadowed[i] != 0) &&
        truth.robust_exponent[i] == robust_exponent_unknown)
      unknown.push_back(i);
  std::vector<std::int8_t> resolved;
  if (!unknown.empty()) {
    if (!truth.lazy)
      throw std::logic_error(
          "hard-shadow truth: robust exponents unknown and nothing to compute them");
    truth.lazy->resolve(unknown, resolved);
  }
  std::size_t next_resolved = 0;

  for (std::size_t i = 0; i < shadowed.size(); ++i) {
    const BandClass band = truth.band[i];
    if (band == BandClass::not_compared) continue;
    ++r.compared;
    const bool answer = shadowed[i] != 0;
    const bool expected = truth.shadowed[i] != 0;
    if (band == BandClass::ambiguous) {
      ++r.ambiguous;
      r.ambiguous_disagreements += answer != expected;
    } else {
      ++r.robust;
      if (answer != expected) ++(expected ? r.leaks : r.false_shadows);
    }
    if (answer != expected) {
      std::int8_t exponent = truth.robust_exponent[i];
      if (exponent == robust_exponent_unknown) exponent = resolved[next_resolved++];
      // Robust at 2^e for every e <= robust_exponent.
      for (int e = band_min_exponent; e <= band_max_exponent && e <= exponent; ++e)
        ++curve[e - band_min_exponent];
    }
  }
  for (int e = band_min_exponent; e <= band_max_exponent; ++e)
    r.mismatch_curve.emplace_back(e, curve[e - band_min_exponent]);

  const std::uint64_t mismatches = r.leaks + r.false_shadows;
  if (mismatches > 0) {
    r.verdict = Verdict::fail;
    r.reason = std::to_string(mismatches) + " robust mismatches (" + std::to_string(r.leaks) +
               " leaks, " + std::to_string(r.false_shadows) + " false shadows) of " +
               std::to_string(r.robust) + " robust samples";
  } else if (chance_of_at_least(r.ambiguous_disagreements, r.ambiguous) <=
             quality_warning_probability) {
    r.verdict = Verdict::quality_warning;
    r.reason = "right on every robust sample, but " + std::to_string(r.ambiguous_disagreements) +
               " of " + std::to_string(r.ambiguous) +
               " ambiguous samples disagree with the exact answer";
  } else {
    r.verdict = Verdict::pass;
    r.reason = "right on all " + std::to_string(r.robust) + " robust samples; " +
               std::to_string(r.ambiguous_disagreements) + " of " + std::to_string(r.ambiguous) +
               " ambiguous samples disagree";
  }
  return r;
}

}  // namespace shadowcts
