#include "shadowcts/hard_shadow_truth.h"

#include <stdexcept>

namespace shadowcts {

void resolve_robust_exponents(HardShadowTruth& truth, std::vector<std::size_t> samples) {
  if (samples.empty())
    for (std::size_t i = 0; i < truth.band.size(); ++i)
      if (truth.band[i] != BandClass::not_compared) samples.push_back(i);
  std::vector<std::size_t> unknown;
  for (const std::size_t i : samples)
    if (truth.robust_exponent[i] == robust_exponent_unknown) unknown.push_back(i);
  if (unknown.empty()) return;
  if (!truth.lazy)
    throw std::logic_error(
        "hard-shadow truth: robust exponents unknown and nothing to compute them");
  std::vector<std::int8_t> exponents;
  truth.lazy->resolve(unknown, exponents);
  for (std::size_t k = 0; k < unknown.size(); ++k) truth.robust_exponent[unknown[k]] = exponents[k];
}

}  // namespace shadowcts
