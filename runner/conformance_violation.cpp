#include "conformance_violation.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <exception>
#include <iterator>
#include <sstream>
#include <vector>

#include "oracles/light_assignment/light_assignment_comparison.h"
#include "oracles/soft_shadow/soft_shadow_comparison.h"
#include "shadowcts/hard_shadow_inputs.h"

namespace shadowcts {
namespace {

bool robust(BandClass band) {
  return band == BandClass::robust_lit || band == BandClass::robust_shadowed;
}

std::optional<Violation> hard_shadow_violation(const AlgorithmOutput& output,
                                               const ViewSamples& samples,
                                               const HardShadowTruth& truth) {
  if (output.shadowed.size() != samples.samples.size())
    return Violation{"shadow mask has the wrong size", std::nullopt};
  for (std::size_t i = 0; i < samples.samples.size(); ++i) {
    if (!robust(truth.band[i]) || output.shadowed[i] == truth.shadowed[i]) continue;
    std::ostringstream what;
    const ViewSample& s = samples.samples[i];
    what.precision(9);
    what << (truth.shadowed[i] ? "leak" : "false shadow") << " at robust sample " << i << " ("
         << s.position.x << ", " << s.position.y << ", " << s.position.z << "), receiver "
         << s.receiver << ": exact oracle says " << (truth.shadowed[i] ? "shadowed" : "lit");
    return Violation{what.str(), i};
  }
  return std::nullopt;
}

std::optional<Violation> soft_shadow_violation(const AlgorithmOutput& output,
                                               const ViewSamples& samples,
                                               const ExactTruths& truths,
                                               const SoftErrorBudget& budget) {
  if (output.visible_fraction.size() != samples.samples.size())
    return Violation{"visible_fraction has the wrong size", std::nullopt};
  for (std::size_t i = 0; i < samples.samples.size(); ++i) {
    const float f = output.visible_fraction[i];
    if (!(f >= 0.0f && f <= 1.0f))
      return Violation{"visible fraction " + std::to_string(f) + " is not in [0, 1]", i};
  }
  if (!truths.soft) return std::nullopt;
  const SoftShadowTruth& truth = *truths.soft;
  if (truths.soft_gross_errors_only) {
    for (std::size_t i = 0; i < samples.samples.size(); ++i) {
      if (!truth.compared[i] || !truth.robust[i]) continue;
      const double exact = truth.visible_fraction[i], f = output.visible_fraction[i];
      if ((exact == 0.0 && f > 0.5) || (exact == 1.0 && f < 0.5)) {
        std::ostringstream what;
        what << "visible fraction " << f << " at robust sample " << i << ", which the exact oracle "
             << (exact == 0.0 ? "puts in full umbra" : "sees fully lit");
        return Violation{what.str(), i};
      }
    }
    return std::nullopt;
  }
  const SoftShadowComparison s = compare_soft_shadows(output.visible_fraction, truth, budget);
  if (s.verdict != Verdict::fail) return std::nullopt;
  return Violation{s.reason,
                   s.worst_sample >= 0 ? std::optional<std::size_t>(s.worst_sample) : std::nullopt};
}

std::optional<Violation> light_list_violation(const AlgorithmOutput& output, const Case& c,
                                              const ViewSamples& samples,
                                              const LightAssignmentTruth& truth) {
  const LightAssignmentComparison cmp = compare_light_lists(output.light_lists, c, samples, truth);
  if (cmp.verdict != Verdict::fail) return std::nullopt;
  std::optional<std::size_t> sample;
  if (!cmp.first_misses.empty())
    sample = cmp.first_misses.front().sample;
  else if (!cmp.first_outside.empty())
    sample = cmp.first_outside.front().sample;
  return Violation{cmp.reason, sample};
}

}  // namespace

ExactTruths exact_truths(const Case& c, const ViewSamples& samples, TruthKinds kinds) {
  ExactTruths truths;
  if (c.light && kinds.hard) {
    // The view is a temporary: drop the lazy exponents that would refer to it (no check here
    // needs the mismatch curve).
    truths.hard = exact_hard_shadow_oracle(hard_shadow_view(c), samples);
    truths.hard->lazy.reset();
  }
  if (c.light && c.light->kind == ShadowLightKind::sun_disk && kinds.soft)
    truths.soft = exact_soft_shadow_oracle(c, samples);
  if (!c.ranged_lights.empty() && kinds.lights) {
    truths.lights = exact_light_assignment_oracle(c, samples, false);
    truths.lights_by_normal_rule = exact_light_assignment_oracle(c, samples, true);
  }
  return truths;
}

std::optional<Violation> output_violation(const Algorithm& algorithm, const std::string& variant,
                                          const Case& c, const ViewSamples& samples,
                                          const AlgorithmOutput& output,
                                          const ExactTruths& truths) {
  switch (algorithm.info().capabilities.output) {
    case OutputKind::hard_shadow:
      return truths.hard ? hard_shadow_violation(output, samples, *truths.hard) : std::nullopt;
    case OutputKind::soft_shadow:
      return soft_shadow_violation(output, samples, truths, algorithm.soft_error_budget(variant));
    case OutputKind::light_lists: {
      const std::optional<LightAssignmentTruth>& truth =
          light_lists_use_normal_rule(variant) ? truths.lights_by_normal_rule : truths.lights;
      return truth ? light_list_violation(output, c, samples, *truth) : std::nullopt;
    }
  }
  return std::nullopt;
}

std::optional<Violation> difference_from_reference(OutputKind kind, const ViewSamples& samples,
                                                   const AlgorithmOutput& port,
                                                   const AlgorithmOutput& reference) {
  const auto list_of = [](const LightLists& lists, std::size_t sample) {
    std::vector<std::uint32_t> list;
    const std::uint32_t k = lists.list_of_sample[sample];
    if (k != LightLists::no_list)
      list.assign(lists.lights.begin() + lists.offsets[k],
                  lists.lights.begin() + lists.offsets[k + 1]);
    std::sort(list.begin(), list.end());
    return list;
  };
  for (std::size_t i = 0; i < samples.samples.size(); ++i) {
    if (samples.samples[i].sample_class != SampleClass::regular) continue;
    if (kind == OutputKind::soft_shadow &&
        std::bit_cast<std::uint32_t>(port.visible_fraction[i]) !=
            std::bit_cast<std::uint32_t>(reference.visible_fraction[i])) {
      std::ostringstream what;
      what.precision(9);
      what << "visible fraction " << port.visible_fraction[i] << " at sample " << i
           << ", the reference's " << reference.visible_fraction[i];
      return Violation{what.str(), i};
    }
    if (kind == OutputKind::light_lists) {
      const std::vector<std::uint32_t> a = list_of(port.light_lists, i),
                                       b = list_of(reference.light_lists, i);
      if (a == b) continue;
      std::vector<std::uint32_t> only_port, only_reference;
      std::set_difference(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(only_port));
      std::set_difference(b.begin(), b.end(), a.begin(), a.end(),
                          std::back_inserter(only_reference));
      std::ostringstream what;
      what << "the list of sample " << i << " has " << a.size() << " lights, the reference's "
           << b.size();
      if (!only_port.empty()) what << "; light " << only_port.front() << " only in the port's";
      if (!only_reference.empty())
        what << "; light " << only_reference.front() << " only in the reference's";
      return Violation{what.str(), i};
    }
  }
  return std::nullopt;
}

std::optional<Violation> find_violation(const Algorithm& algorithm, const std::string& variant,
                                        const Case& original, const ViewSamples& samples,
                                        const ExactTruths& truths,
                                        std::optional<AlgorithmOutput>* output) {
  const Case c = algorithm.info().capabilities.output == OutputKind::hard_shadow
                     ? hard_shadow_view(original)
                     : original;
  if (algorithm.unsupported_reason(c, samples, variant)) return std::nullopt;
  std::optional<AlgorithmOutput> answer;
  try {
    answer = algorithm.run(c, samples, variant);
  } catch (const std::exception& e) {
    return Violation{std::string("threw on a valid case: ") + e.what(), std::nullopt};
  }
  std::optional<Violation> violation =
      output_violation(algorithm, variant, c, samples, *answer, truths);
  if (output) *output = std::move(answer);
  return violation;
}

std::optional<Violation> violation_on(const Algorithm& algorithm, const std::string& variant,
                                      const fuzzing::SampleCase& candidate) {
  const OutputKind kind = algorithm.info().capabilities.output;
  return find_violation(algorithm, variant, candidate.c, candidate.samples,
                        exact_truths(candidate.c, candidate.samples,
                                     {.hard = kind == OutputKind::hard_shadow,
                                      .soft = kind == OutputKind::soft_shadow,
                                      .lights = kind == OutputKind::light_lists}));
}

}  // namespace shadowcts
