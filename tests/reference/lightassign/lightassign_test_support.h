#pragma once
// Runs a lightassign variant on a case and compares it with the exact oracle, as the runner does.
#include <memory>
#include <string>

#include "oracles/light_assignment/light_assignment_comparison.h"
#include "reference/lightassign/lightassign_algorithm.h"
#include "shadowcts/light_assignment_oracle.h"
#include "shadowcts/view_samples.h"

namespace shadowcts::testing {

inline const Algorithm& lightassign() {
  static const std::unique_ptr<Algorithm> algorithm = make_lightassign();
  return *algorithm;
}

struct VariantRun {
  AlgorithmOutput output;
  LightAssignmentComparison comparison;
};

inline std::uint64_t counter(const AlgorithmOutput& output, const std::string& name) {
  for (const auto& [key, value] : output.counters)
    if (key == name) return value;
  return ~std::uint64_t(0);
}

// truth_plain / truth_normals: the oracle without and with the normal rule for these samples.
inline VariantRun run_and_compare(const Case& c, const ViewSamples& samples,
                                  const std::string& variant,
                                  const LightAssignmentTruth& truth_plain,
                                  const LightAssignmentTruth& truth_normals) {
  VariantRun run;
  run.output = lightassign().run(c, samples, variant);
  run.comparison =
      compare_light_lists(run.output.light_lists, c, samples,
                          light_lists_use_normal_rule(variant) ? truth_normals : truth_plain);
  return run;
}

}  // namespace shadowcts::testing
