#include "conformance_violation.h"

#include <exception>
#include <sstream>

#include "shadowcts/hard_shadow_inputs.h"

namespace shadowcts {
namespace {

bool robust(BandClass band) {
  return band == BandClass::robust_lit || band == BandClass::robust_shadowed;
}

}  // namespace

std::optional<HardShadowTruth> exact_hard_shadow_truth(const Case& c, const ViewSamples& samples) {
  if (!c.light) return std::nullopt;
  // The view is a temporary: drop the lazy exponents that would refer to it (no check here
  // needs the mismatch curve).
  HardShadowTruth truth = exact_hard_shadow_oracle(hard_shadow_view(c), samples);
  truth.lazy.reset();
  return truth;
}

std::optional<Violation> find_violation(const Algorithm& algorithm, const std::string& variant,
                                        const Case& original, const ViewSamples& samples,
                                        const std::optional<HardShadowTruth>& truth) {
  const OutputKind kind = algorithm.info().capabilities.output;
  const Case c = kind == OutputKind::hard_shadow ? hard_shadow_view(original) : original;
  if (algorithm.unsupported_reason(c, samples, variant)) return std::nullopt;
  AlgorithmOutput output;
  try {
    output = algorithm.run(c, samples, variant);
  } catch (const std::exception& e) {
    return Violation{std::string("threw on a valid case: ") + e.what(), std::nullopt};
  }
  if (kind == OutputKind::soft_shadow) {
    if (output.visible_fraction.size() != samples.samples.size())
      return Violation{"visible_fraction has the wrong size", std::nullopt};
    for (std::size_t i = 0; i < samples.samples.size(); ++i) {
      const float f = output.visible_fraction[i];
      if (!(f >= 0.0f && f <= 1.0f))
        return Violation{"visible fraction " + std::to_string(f) + " is not in [0, 1]", i};
    }
    return std::nullopt;
  }
  if (kind != OutputKind::hard_shadow || !truth) return std::nullopt;
  if (output.shadowed.size() != samples.samples.size())
    return Violation{"shadow mask has the wrong size", std::nullopt};
  for (std::size_t i = 0; i < samples.samples.size(); ++i) {
    if (!robust(truth->band[i]) || output.shadowed[i] == truth->shadowed[i]) continue;
    std::ostringstream what;
    const ViewSample& s = samples.samples[i];
    what.precision(9);
    what << (truth->shadowed[i] ? "leak" : "false shadow") << " at robust sample " << i << " ("
         << s.position.x << ", " << s.position.y << ", " << s.position.z << "), receiver "
         << s.receiver << ": exact oracle says " << (truth->shadowed[i] ? "shadowed" : "lit");
    return Violation{what.str(), i};
  }
  return std::nullopt;
}

std::optional<Violation> violation_on(const Algorithm& algorithm, const std::string& variant,
                                      const fuzzing::SampleCase& candidate) {
  return find_violation(algorithm, variant, candidate.c, candidate.samples,
                        exact_hard_shadow_truth(candidate.c, candidate.samples));
}

}  // namespace shadowcts
