#pragma once
// One record of a run: a case x algorithm x variant x backend, with what it measured.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "shadowcts/algorithm.h"
#include "shadowcts/hard_shadow_comparison.h"
#include "shadowcts/verdict.h"

namespace shadowcts {

struct CaseSummary {
  std::string name, source;
  std::string light;  // "point", "directional", "sun_disk", "none"
  std::uint64_t triangles = 0, ranged_lights = 0;
  std::uint32_t width = 0, height = 0;
  std::uint64_t regular = 0, sky = 0, back_facing = 0;
  std::string samples_from;  // "embree primary rays" or the G-buffer path
  std::string oracle_method;
  bool oracle_exact = false;
  double eps_rel = 0, tau = 0, oracle_ms = 0;
  std::uint64_t robust_lit = 0, robust_shadowed = 0, ambiguous = 0;
  std::vector<std::string> left_out;  // "what: why"
  std::string oracle_image;           // relative to the output folder; empty if none
};

struct RunRecord {
  std::string case_name;
  std::string test_name;  // dotted: <output>.<algorithm>.<variant>.<backend>.<case>
  std::string algorithm, variant, backend;
  OutputKind output = OutputKind::hard_shadow;
  Verdict verdict = Verdict::pass;
  std::string reason;
  std::vector<double> run_ms;  // every timed repeat
  double median_ms = 0;
  Counters counters;
  std::optional<HardShadowComparison> hard;
  std::vector<std::string> images;  // relative to the output folder
};

std::string output_kind_name(OutputKind kind);

}  // namespace shadowcts
