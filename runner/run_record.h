#pragma once
// One record of a run: a case x algorithm x variant x backend, with what it measured.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "shadowcts/algorithm.h"
#include "shadowcts/verdict.h"

namespace shadowcts {

struct CaseSummary {
  std::string name, source;
  std::string light;  // "point", "directional", "sun_disk", "none"
  std::uint64_t triangles = 0, ranged_lights = 0;
  std::uint32_t width = 0, height = 0;
  std::uint64_t regular = 0, sky = 0, back_facing = 0;
  std::string samples_from;  // "embree primary rays" or the G-buffer path
  // Receivers the suite found in a G-buffer without ids: from, tau, unique, ambiguous; empty
  // (null) when the samples name their receivers.
  nlohmann::ordered_json receivers;
  // Per output kind compared ("hard", "soft", "lights"): the oracle's method, time, figures.
  nlohmann::ordered_json oracles = nlohmann::ordered_json::object();
  std::vector<std::string> left_out;  // "what: why"
};

// One phase's times over the timed repeats (AlgorithmOutput::phase_ms).
struct PhaseRuns {
  std::string name;            // "build", "query", ...
  std::vector<double> run_ms;  // one per timed repeat, in the order of RunRecord::run_ms
  double median_ms = 0;
};

struct RunRecord {
  std::string case_name;
  std::string image_folder;  // the case's folder under images/ (case_image_folders)
  std::string test_name;     // dotted: <output>.<algorithm>.<variant>.<backend>.<case>
  std::string algorithm, variant, backend;
  OutputKind output = OutputKind::hard_shadow;
  bool approximate = false;     // Capabilities::approximate
  double mismatch_ceiling = 0;  // approximate: Algorithm::robust_mismatch_ceiling(variant)
  SoftErrorBudget soft_budget;  // soft_shadow outputs: what the variant declares
  Verdict verdict = Verdict::pass;
  std::string reason;
  // A Fail that a documented limit of the method explains: why (runner/known_limits.h); else "".
  std::string known_limit;
  std::vector<double> run_ms;  // every timed repeat
  double median_ms = 0;
  // The phases the algorithm declares for the variant (Algorithm::timed_phases), in its order;
  // empty when it declares none.
  std::vector<PhaseRuns> phases;
  Counters counters;
  nlohmann::ordered_json error;     // the comparison's figures (results.json "error")
  std::string headline;             // the key figures in a few words, for the terminal
  std::vector<std::string> images;  // relative to the output folder
  std::string reproduce;            // the command that reruns just this record
};

std::string output_kind_name(OutputKind kind);

}  // namespace shadowcts
