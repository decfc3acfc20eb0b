#pragma once
// The conformance property of a case with explicit samples, for one algorithm x variant: it
// supports the case and then never throws, answers NaN or a fraction outside [0, 1], and agrees
// with the exact truths it is given as the runner's verdict would: hard shadows on every sample
// the oracle calls robust, soft shadows within the variant's declared budget (or, where asked,
// without gross errors), light lists complete and sound. The geometry fuzz targets check it for
// every registered algorithm (fuzz/support/conformance_check.h); `shadowcts certify` for a plugin's
// variant when it shrinks a failing fuzz case.
#include <cstddef>
#include <optional>
#include <string>

#include "fixtures/fuzz/sample_case.h"
#include "shadowcts/algorithm.h"
#include "shadowcts/hard_shadow_oracle.h"
#include "shadowcts/light_assignment_oracle.h"
#include "shadowcts/soft_shadow_oracle.h"

namespace shadowcts {

// What went wrong for one algorithm on one case. `sample` is the first failing sample where one
// exists (a throw has none).
struct Violation {
  std::string what;
  std::optional<std::size_t> sample;
};

// The exact truths of a case; a kind of output is compared only where its truth is present.
struct ExactTruths {
  // Of the sun disk's centre direction for a sun disk (as the runner compares hard-shadow
  // algorithms there); samples may be marked not_compared (a peer's documented limit).
  std::optional<HardShadowTruth> hard;
  std::optional<SoftShadowTruth> soft;                                // a sun disk
  std::optional<LightAssignmentTruth> lights, lights_by_normal_rule;  // ranged lights
  // false: soft fractions are judged against the variant's declared budget, as the runner does.
  // true: only for gross errors, which no faithful variant makes whatever its budget: a robust
  // sample in full umbra answered more than half lit, or one in full light answered more than
  // half shadowed (every variant samples points inside the disk, where it is then exact up to
  // rounding).
  bool soft_gross_errors_only = false;
};

// Which exact oracles exact_truths runs.
struct TruthKinds {
  bool hard = true, soft = true, lights = true;
};

// The exact truths of the case's lights, of the kinds asked for.
ExactTruths exact_truths(const Case& c, const ViewSamples& samples, TruthKinds kinds = {});

// Whether `output`, the algorithm's answer on the case, keeps the property (nullopt) or not.
std::optional<Violation> output_violation(const Algorithm& algorithm, const std::string& variant,
                                          const Case& c, const ViewSamples& samples,
                                          const AlgorithmOutput& output, const ExactTruths& truths);

// The first regular sample where a port's output differs from its reference's (soft shadows: the
// visible fraction bit for bit; light lists: the sample's list as a set), or nullopt. For outputs
// of one kind that each keep the property; hard shadows are not compared (ports may differ on
// ambiguous samples).
std::optional<Violation> difference_from_reference(OutputKind kind, const ViewSamples& samples,
                                                   const AlgorithmOutput& port,
                                                   const AlgorithmOutput& reference);

// nullopt when the algorithm answers NotSupported or keeps the property. `output`, where given,
// receives what the algorithm answered, when it ran without throwing.
std::optional<Violation> find_violation(const Algorithm& algorithm, const std::string& variant,
                                        const Case& c, const ViewSamples& samples,
                                        const ExactTruths& truths,
                                        std::optional<AlgorithmOutput>* output = nullptr);

// find_violation against the case's own exact truths.
std::optional<Violation> violation_on(const Algorithm& algorithm, const std::string& variant,
                                      const fuzzing::SampleCase& candidate);

}  // namespace shadowcts
