#pragma once
// Ground truth for hard shadows: the answer at each sample and its class in the ambiguity band.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace shadowcts {

enum class BandClass : std::uint8_t { not_compared, robust_lit, robust_shadowed, ambiguous };

// The mismatch curve runs over eps_rel = 2^-24 ... 2^-10.
inline constexpr int band_min_exponent = -24;
inline constexpr int band_max_exponent = -10;
// robust_exponent value of a sample that is ambiguous even at eps_rel = 2^-24.
inline constexpr std::int8_t ambiguous_at_every_exponent = band_min_exponent - 1;

// robust_exponent value of a sample whose exponent the oracle computes only on demand.
inline constexpr std::int8_t robust_exponent_unknown = 127;

// Computes robust_exponent on demand: the exact oracle finds a sample's answer and class at
// eps_rel cheaply, while its exponent needs every caster within 2^-10 S of the shadow query; the
// mismatch curve needs it only where an implementation answers differently.
class LazyRobustExponents {
 public:
  virtual ~LazyRobustExponents() = default;
  // out[k] = robust_exponent of samples[k] (regular samples). Thread-safe; deterministic.
  virtual void resolve(const std::vector<std::size_t>& samples,
                       std::vector<std::int8_t>& out) const = 0;
};

struct HardShadowTruth {
  std::string method;  // how it was obtained, e.g. "exact: CGAL Epick predicates, AABB tree"
  bool exact = false;  // false: fast oracle (float rays), band estimated
  double eps_rel = 0.0;
  double tau = 0.0;                    // eps_rel * case scale
  std::vector<std::uint8_t> shadowed;  // answer at the unmoved sample, 1 = shadowed
  std::vector<BandClass> band;         // class at eps_rel; not_compared for sky / back-facing
  // Per sample: the largest e in [band_min_exponent, band_max_exponent] such that the sample is
  // robust at eps_rel = 2^e (robustness is monotone in eps_rel, so this gives the whole curve);
  // ambiguous_at_every_exponent when none; robust_exponent_unknown where `lazy` computes it on
  // demand (resolve_robust_exponents). Not meaningful for not_compared samples.
  std::vector<std::int8_t> robust_exponent;
  std::shared_ptr<const LazyRobustExponents> lazy;
};

// Fills in every robust_exponent_unknown entry of the listed samples (all regular samples when
// `samples` is empty) from truth.lazy.
void resolve_robust_exponents(HardShadowTruth& truth, std::vector<std::size_t> samples = {});

}  // namespace shadowcts
