#pragma once
// Per case and output kind: the oracle's truth, computed once, and the judgement of every run
// against it. One implementation per output kind (hard shadows, soft shadows, light lists).
#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "run_record.h"
#include "shadowcts/algorithm.h"
#include "shadowcts/view_samples.h"

namespace shadowcts {

struct OracleSummary {
  std::string method;  // how the truth was obtained
  bool exact = false;  // false: sampled or estimated (the method says how)
  double time_ms = 0;
  std::string plan_line;           // what the plan prints after "oracle:"
  nlohmann::ordered_json details;  // kind-specific figures for results.json
};

// The reason of a record that ran but had nothing to judge (NotSupported, never Pass: "right on
// all 0 robust samples" would be a false green): "no robust sample to judge: N ambiguous, M sky,
// K back-facing".
inline std::string nothing_to_judge(const ViewSamples& samples, std::uint64_t ambiguous) {
  return "no robust sample to judge: " + std::to_string(ambiguous) + " ambiguous, " +
         std::to_string(samples.count(SampleClass::sky)) + " sky, " +
         std::to_string(samples.count(SampleClass::back_facing)) + " back-facing";
}

class CaseEvaluation {
 public:
  virtual ~CaseEvaluation() = default;
  const OracleSummary& oracle() const { return oracle_; }
  // Fills record.error, record.headline and record.images, and sets record.verdict and
  // record.reason unless the record already failed (e.g. nondeterministic repeats).
  virtual void judge(const AlgorithmOutput& output, RunRecord& record) const = 0;
  // The samples the output got wrong where the oracle is sure (hard shadows: robust mismatches),
  // for telling a known limit on some samples from a failure elsewhere. Empty where the verdict
  // rests on other figures (soft budgets, light lists).
  virtual std::vector<std::size_t> robust_mismatches(const AlgorithmOutput&) const { return {}; }

 protected:
  OracleSummary oracle_;
};

}  // namespace shadowcts
