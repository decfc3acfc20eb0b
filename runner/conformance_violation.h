#pragma once
// The conformance property of a case with explicit samples, for one algorithm x variant: it
// supports the case and then never throws, answers NaN or a fraction outside [0, 1], and (hard
// shadows) agrees with the exact oracle on every sample the oracle calls robust. The geometry fuzz
// targets check it for every registered algorithm (fuzz/support/conformance_check.h);
// `shadowcts certify` for a plugin's variant when it shrinks a failing fuzz case.
#include <cstddef>
#include <optional>
#include <string>

#include "fixtures/fuzz/sample_case.h"
#include "shadowcts/algorithm.h"
#include "shadowcts/hard_shadow_oracle.h"

namespace shadowcts {

// What went wrong for one algorithm on one case. `sample` is the first failing sample where one
// exists (a throw has none).
struct Violation {
  std::string what;
  std::optional<std::size_t> sample;
};

// The exact hard-shadow truth, of the sun disk's centre direction for a sun disk (as the runner
// compares hard-shadow algorithms there); nullopt without a shadow light.
std::optional<HardShadowTruth> exact_hard_shadow_truth(const Case& c, const ViewSamples& samples);

// nullopt when the algorithm answers NotSupported or keeps the property; `truth` may have samples
// marked not_compared (a peer's documented limit) or be nullopt (nothing compared).
std::optional<Violation> find_violation(const Algorithm& algorithm, const std::string& variant,
                                        const Case& c, const ViewSamples& samples,
                                        const std::optional<HardShadowTruth>& truth);

// find_violation against the case's own exact truth.
std::optional<Violation> violation_on(const Algorithm& algorithm, const std::string& variant,
                                      const fuzzing::SampleCase& candidate);

}  // namespace shadowcts
