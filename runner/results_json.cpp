#include "results_json.h"

#include <algorithm>

#include <nlohmann/json.hpp>

#include "atomic_file.h"
#include "machine_info.h"

namespace shadowcts {
namespace {

using nlohmann::ordered_json;

ordered_json case_json(const CaseSummary& c) {
  ordered_json j;
  j["name"] = c.name;
  j["source"] = c.source;
  j["light"] = c.light;
  j["triangles"] = c.triangles;
  j["ranged_lights"] = c.ranged_lights;
  j["resolution"] = {c.width, c.height};
  j["samples"] = {{"from", c.samples_from},
                  {"regular", c.regular},
                  {"sky", c.sky},
                  {"back_facing", c.back_facing}};
  if (!c.receivers.is_null()) j["samples"]["receivers"] = c.receivers;
  j["oracles"] = c.oracles;
  j["left_out"] = c.left_out;
  return j;
}

// Median, min, max and every run of one time (the whole call, or a phase); min and max are
// absent when nothing was timed (a crash before the first repeat).
ordered_json timing_json(double median_ms, const std::vector<double>& runs) {
  ordered_json j;
  j["median"] = median_ms;
  if (!runs.empty()) {
    j["min"] = *std::min_element(runs.begin(), runs.end());
    j["max"] = *std::max_element(runs.begin(), runs.end());
  }
  j["runs"] = runs;
  return j;
}

ordered_json record_json(const RunRecord& r) {
  ordered_json j;
  j["name"] = r.test_name;
  j["case"] = r.case_name;
  j["output"] = output_kind_name(r.output);
  j["algorithm"] = r.algorithm;
  j["variant"] = r.variant;
  j["backend"] = r.backend;
  j["verdict"] = verdict_name(r.verdict);
  j["reason"] = r.reason;
  if (!r.known_limit.empty()) j["known_limit"] = r.known_limit;
  j["reproduce"] = r.reproduce;
  // Left out by the plan: it never ran. A NotSupported that ran (nothing to judge) keeps its
  // figures.
  if (r.verdict == Verdict::not_supported && r.run_ms.empty()) return j;
  j["time_ms"] = timing_json(r.median_ms, r.run_ms);
  if (!r.phases.empty()) {
    ordered_json phases = ordered_json::object();
    for (const PhaseRuns& phase : r.phases)
      phases[phase.name] = timing_json(phase.median_ms, phase.run_ms);
    j["time_ms"]["phases"] = phases;
  }
  ordered_json counters = ordered_json::object();
  for (const auto& [name, value] : r.counters) counters[name] = value;
  j["counters"] = counters;
  j["error"] = r.error;
  j["images"] = r.images;
  return j;
}

}  // namespace

void write_results_json(const std::filesystem::path& path, const std::vector<CaseSummary>& cases,
                        const std::vector<RunRecord>& records, std::uint32_t threads,
                        const MachineInfo& machine) {
  ordered_json root;
  root["schema"] = results_schema;
  root["machine"] = {{"cpu", machine.cpu},
                     {"hardware_threads", machine.hardware_threads},
                     {"isa", machine.isa},
                     {"isa_targets", machine.isa_targets}};
  root["threads"] = threads;
  root["timing"] =
      "one untimed warm-up run per record, then time_ms.runs timed repeats; median, min and max "
      "over them; time_ms.phases: the same for the phases the algorithm times inside each run; "
      "an emulated backend (cuda-emu) runs once unless --repeat is given, without a warm-up: "
      "that run is judged and timed, and its time measures the CUDA-subset emulator, not a GPU";
  root["cases"] = ordered_json::array();
  for (const CaseSummary& c : cases) root["cases"].push_back(case_json(c));
  root["results"] = ordered_json::array();
  for (const RunRecord& r : records) root["results"].push_back(record_json(r));
  write_file_atomically(path, root.dump(2) + "\n");
}

}  // namespace shadowcts
