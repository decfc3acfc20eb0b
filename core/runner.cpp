#include "shadowcts/runner.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <map>
#include <memory>
#include <ostream>
#include <set>
#include <sstream>

#include <tbb/global_control.h>
#include <tbb/info.h>

#include "case_evaluation.h"
#include "hard_shadow_evaluation.h"
#include "heat_map.h"
#include "image_paths.h"
#include "junit_xml.h"
#include "light_assignment_evaluation.h"
#include "machine_info.h"
#include "oracles/hard_shadow_inputs.h"
#include "report/html_report.h"
#include "results_json.h"
#include "run_record.h"
#include "shadowcts/case_manifest.h"
#include "shadowcts/errors.h"
#include "shadowcts/fixtures.h"
#include "shadowcts/gbuffer_exr.h"
#include "shadowcts/registry.h"
#include "soft_shadow_evaluation.h"

namespace shadowcts {
namespace {

using Clock = std::chrono::steady_clock;

double elapsed_ms(Clock::time_point since) {
  return std::chrono::duration<double, std::milli>(Clock::now() - since).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string light_name(const Case& c) {
  if (!c.light) return "none";
  switch (c.light->kind) {
    case ShadowLightKind::point:
      return "point";
    case ShadowLightKind::directional:
      return "directional";
    case ShadowLightKind::sun_disk:
      return "sun_disk";
  }
  return "none";
}

// `selectors` receives, per case, the option that selects it again ("--fixture NAME" or
// "--case FILE"), for the reproducer command of each record.
std::vector<Case> load_cases(const RunOptions& options, std::vector<std::string>& selectors) {
  std::vector<Case> cases;
  std::vector<std::string> fixtures = options.fixtures;
  if (options.suite == "stiff") {
    const std::vector<std::string> stiff = stiff_fixtures();
    fixtures.insert(fixtures.end(), stiff.begin(), stiff.end());
  } else if (!options.suite.empty()) {
    throw UsageError("--suite " + options.suite + ": unknown suite (known: stiff)");
  }
  if (fixtures.empty() && options.case_files.empty()) fixtures = default_fixtures();
  // Shards take every n-th case of the whole list, fixtures first, so that shards of one run
  // partition it the same way on every machine. Only this shard's cases are built.
  std::size_t position = 0;
  auto in_shard = [&] { return position++ % options.shard_count == options.shard_index; };
  for (const std::string& name : fixtures)
    if (in_shard()) {
      cases.push_back(make_fixture(name));
      selectors.push_back("--fixture " + name);
    }
  for (const std::string& file : options.case_files)
    if (in_shard()) {
      cases.push_back(load_case_manifest(file));
      selectors.push_back("--case " + file);
    }
  for (Case& c : cases) {
    if (options.eps_rel) c.parameters.eps_rel = *options.eps_rel;
    if (options.repeats) c.parameters.repeats = *options.repeats;
    if (options.threads) c.parameters.threads = *options.threads;
    validate(c);
  }
  for (std::size_t i = 0; i < cases.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (cases[i].name == cases[j].name)
        throw UsageError("case '" + cases[i].name + "' is given twice");
  return cases;
}

struct PlannedRun {
  const Algorithm* algorithm;
  std::string variant;
};

bool selected(const RunOptions& options, const AlgorithmInfo& meta, const std::string& variant) {
  if (!options.backend.empty() && meta.backend != options.backend) return false;
  if (options.algorithms.empty()) return true;
  for (const AlgorithmSelection& s : options.algorithms)
    if (s.id == meta.id && (s.variant.empty() || s.variant == variant)) return true;
  return false;
}

void check_selection(const RunOptions& options, const Registry& registry) {
  for (const AlgorithmSelection& s : options.algorithms) {
    bool found = false;
    for (const auto& a : registry.algorithms()) {
      const AlgorithmInfo& meta = a->info();
      if (meta.id != s.id) continue;
      if (!options.backend.empty() && meta.backend != options.backend) continue;
      if (s.variant.empty() || std::count(meta.variants.begin(), meta.variants.end(), s.variant))
        found = true;
    }
    if (!found)
      throw UsageError("--algorithm " + s.id + (s.variant.empty() ? "" : ":" + s.variant) +
                       (options.backend.empty() ? "" : " --backend " + options.backend) +
                       ": no such registered algorithm (see `shadowcts list`)");
  }
}

class Progress {
 public:
  Progress(bool enabled, std::ostream& err) : enabled_(enabled), err_(err) {}
  void show(const std::string& line) {
    if (enabled_) err_ << "\r\033[K" << line << std::flush;
  }
  ~Progress() {
    if (enabled_) err_ << "\r\033[K" << std::flush;
  }

 private:
  bool enabled_;
  std::ostream& err_;
};

RunRecord new_record(const Case& c, const std::string& selector, const Algorithm& algorithm,
                     const std::string& variant) {
  const AlgorithmInfo& meta = algorithm.info();
  RunRecord record;
  record.case_name = c.name;
  record.algorithm = meta.id;
  record.variant = variant;
  record.backend = meta.backend;
  record.output = meta.capabilities.output;
  record.approximate = meta.capabilities.approximate;
  if (record.output == OutputKind::soft_shadow)
    record.soft_budget = algorithm.soft_error_budget(variant);
  record.reproduce = "shadowcts run " + selector + " --algorithm " + meta.id + ":" + variant +
                     " --backend " + meta.backend;
  record.test_name = output_kind_name(record.output) + "." + meta.id + "." + variant + "." +
                     meta.backend + "." + c.name;
  return record;
}

// A work counter per sample (the papers' figures), full scale at its largest value.
std::string write_counter_heat_map(const std::filesystem::path& out_dir, const RunRecord& record,
                                   const ViewSamples& samples, const std::string& counter,
                                   const std::vector<std::uint32_t>& per_sample) {
  if (per_sample.size() != samples.samples.size())
    throw std::runtime_error("per-sample counter '" + counter + "' has " +
                             std::to_string(per_sample.size()) + " entries, not one per sample");
  const std::uint32_t full = *std::max_element(per_sample.begin(), per_sample.end());
  return write_png_and_exr(out_dir, algorithm_image_stem(record) + "." + counter,
                           count_heat_map(samples, per_sample, full));
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& name : names) out += (out.empty() ? "" : ", ") + name;
  return "{" + out + "}";
}

// An output reports exactly the phases its algorithm declares for the variant, each a time.
void check_phases(const std::vector<std::string>& declared, const AlgorithmOutput& output) {
  std::vector<std::string> reported;
  for (const auto& [name, ms] : output.phase_ms) {
    reported.push_back(name);
    if (!std::isfinite(ms) || ms < 0)
      throw std::logic_error("phase '" + name + "' reports " + std::to_string(ms) + " ms");
  }
  if (reported != declared)
    throw std::logic_error("the output reports phases " + joined(reported) +
                           " but the algorithm declares " + joined(declared));
}

// " (build 1.23 + query 4.56 ms)" for the phases' medians, or "".
std::string phases_text(const RunRecord& r) {
  if (r.phases.empty() || r.run_ms.empty() || r.verdict == Verdict::crash) return "";
  std::ostringstream text;
  text << std::fixed << std::setprecision(2);
  for (std::size_t k = 0; k < r.phases.size(); ++k)
    text << (k ? " + " : "") << r.phases[k].name << " " << r.phases[k].median_ms;
  return " (" + text.str() + " ms)";
}

bool same_results(const AlgorithmOutput& a, const AlgorithmOutput& b) {
  const LightLists &x = a.light_lists, &y = b.light_lists;
  return a.shadowed == b.shadowed && a.visible_fraction == b.visible_fraction &&
         x.offsets == y.offsets && x.lights == y.lights && x.list_of_sample == y.list_of_sample;
}

std::unique_ptr<CaseEvaluation> evaluate(OutputKind kind, const Case& c, const ViewSamples& samples,
                                         OracleChoice choice, const std::filesystem::path& out_dir,
                                         std::vector<std::string>& left_out) {
  switch (kind) {
    case OutputKind::hard_shadow:
      return evaluate_hard_shadows(c, samples, choice, out_dir, left_out);
    case OutputKind::soft_shadow:
      return evaluate_soft_shadows(c, samples, choice, out_dir, left_out);
    case OutputKind::light_lists:
      return evaluate_light_assignment(c, samples, out_dir);
  }
  throw std::logic_error("no evaluation for " + output_kind_name(kind) + " outputs");
}

void print_summary(std::ostream& out, const std::vector<RunRecord>& records,
                   const MachineInfo& machine, std::uint32_t threads) {
  out << "\nsummary  (" << machine.cpu << ", " << machine.hardware_threads
      << " hardware threads, Highway ISA " << machine.isa << "; " << threads
      << " worker threads)\n";
  out << std::left << std::setw(34) << "case" << std::setw(38) << "algorithm" << std::setw(15)
      << "verdict" << std::right << std::setw(11) << "median ms"
      << "   figures\n";
  for (const RunRecord& r : records) {
    if (r.verdict == Verdict::not_supported) continue;  // the plan's "left out" lines say why
    out << std::left << std::setw(34) << r.case_name << std::setw(38)
        << (r.algorithm + ":" + r.variant + " [" + r.backend + "]") << std::setw(15)
        << verdict_name(r.verdict) << std::right;
    if (r.verdict == Verdict::crash) {
      out << "   " << r.reason << "\n";
      continue;
    }
    out << std::setw(11) << std::fixed << std::setprecision(2) << r.median_ms << "   " << r.headline
        << phases_text(r) << "\n";
  }
  std::size_t counts[5] = {};
  for (const RunRecord& r : records) ++counts[int(r.verdict)];
  out << "\n"
      << records.size() << " results: " << counts[int(Verdict::pass)] << " Pass, "
      << counts[int(Verdict::fail)] << " Fail, " << counts[int(Verdict::quality_warning)]
      << " QualityWarning, " << counts[int(Verdict::not_supported)] << " NotSupported, "
      << counts[int(Verdict::crash)] << " Crash\n";
}

}  // namespace

std::string output_kind_name(OutputKind kind) {
  switch (kind) {
    case OutputKind::hard_shadow:
      return "hard";
    case OutputKind::soft_shadow:
      return "soft";
    case OutputKind::light_lists:
      return "lights";
  }
  return "hard";
}

int run_suite(const RunOptions& options, const Registry& registry, std::ostream& out,
              std::ostream& err) {
  check_selection(options, registry);
  std::vector<std::string> selectors;
  const std::vector<Case> cases = load_cases(options, selectors);  // input checked before any work

  const std::uint32_t threads = options.threads.value_or(0)
                                    ? *options.threads
                                    : std::uint32_t(tbb::info::default_concurrency());
  tbb::global_control thread_limit(tbb::global_control::max_allowed_parallelism, threads);

  const std::filesystem::path out_dir(options.out_dir);
  std::error_code ec;
  std::filesystem::create_directories(out_dir / "images", ec);
  if (ec) throw UsageError("--out " + options.out_dir + ": cannot create folder: " + ec.message());

  Progress progress(options.progress, err);
  std::vector<CaseSummary> summaries;
  std::vector<RunRecord> records;

  for (std::size_t case_index = 0; case_index < cases.size(); ++case_index) {
    const Case& c = cases[case_index];
    const std::string step = "[" + std::to_string(case_index + 1) + "/" +
                             std::to_string(cases.size()) + "] " + c.name + ": ";
    CaseSummary summary;
    summary.name = c.name;
    summary.source = c.source;
    summary.light = light_name(c);
    summary.triangles = c.triangles.size();
    summary.ranged_lights = c.ranged_lights.size();
    summary.width = c.camera.width;
    summary.height = c.camera.height;

    progress.show(step + "view samples");
    ViewSamples samples;
    if (c.gbuffer_path.empty()) {
      samples = generate_view_samples(c);
      summary.samples_from = "embree primary rays";
    } else {
      samples = read_gbuffer_exr(c.gbuffer_path);
      classify_samples(c, samples, c.gbuffer_path);
      summary.samples_from = c.gbuffer_path;
      summary.left_out.push_back("Embree G-buffer pass: the case brings its G-buffer");
    }
    summary.regular = samples.count(SampleClass::regular);
    summary.sky = samples.count(SampleClass::sky);
    summary.back_facing = samples.count(SampleClass::back_facing);
    if (summary.sky + summary.back_facing > 0)
      summary.left_out.push_back("comparison of " + std::to_string(summary.sky) + " sky and " +
                                 std::to_string(summary.back_facing) +
                                 " back-facing samples: they have no shadow to compare");

    // Plan: which algorithms run, which are left out and why.
    const Case hard_case = hard_shadow_view(c);
    std::vector<PlannedRun> planned;
    std::set<OutputKind> kinds;
    for (const auto& a : registry.algorithms()) {
      const AlgorithmInfo& meta = a->info();
      for (const std::string& variant : meta.variants) {
        if (!selected(options, meta, variant)) continue;
        const OutputKind kind = meta.capabilities.output;
        std::optional<std::string> why = a->unsupported_reason(
            kind == OutputKind::hard_shadow ? hard_case : c, samples, variant);
        if (why) {
          RunRecord record = new_record(c, selectors[case_index], *a, variant);
          record.verdict = Verdict::not_supported;
          record.reason = *why;
          summary.left_out.push_back(meta.id + ":" + variant + " [" + meta.backend + "]: " + *why);
          records.push_back(std::move(record));
          continue;
        }
        kinds.insert(kind);
        planned.push_back({a.get(), variant});
      }
    }
    if (c.light && c.light->kind == ShadowLightKind::sun_disk &&
        kinds.count(OutputKind::hard_shadow))
      summary.left_out.push_back(
          "penumbrae in hard-shadow comparisons: hard-shadow algorithms see the sun disk's centre "
          "direction");
    if (c.light && c.light->kind != ShadowLightKind::sun_disk)
      summary.left_out.push_back("soft-shadow oracle: the light is not a sun disk");
    if (!c.light) summary.left_out.push_back("hard-shadow oracle: the case has no shadow light");
    if (c.ranged_lights.empty())
      summary.left_out.push_back("light-assignment oracle: the case has no ranged lights");

    // Oracles, only for the output kinds that something planned needs.
    std::map<OutputKind, std::unique_ptr<CaseEvaluation>> evaluations;
    for (OutputKind kind : kinds) {
      progress.show(step + output_kind_name(kind) + " oracle");
      evaluations[kind] = evaluate(kind, kind == OutputKind::hard_shadow ? hard_case : c, samples,
                                   options.oracle, out_dir, summary.left_out);
      const OracleSummary& o = evaluations[kind]->oracle();
      summary.oracles[output_kind_name(kind)] =
          nlohmann::ordered_json{{"method", o.method}, {"exact", o.exact}, {"time_ms", o.time_ms}};
      summary.oracles[output_kind_name(kind)].update(o.details);
    }

    out << "case " << c.name << "  (" << summary.triangles << " triangles, " << summary.width << "x"
        << summary.height << " samples: " << summary.regular << " regular, " << summary.sky
        << " sky, " << summary.back_facing << " back-facing; light " << summary.light;
    if (summary.ranged_lights) out << ", " << summary.ranged_lights << " ranged lights";
    out << ")\n";
    for (const auto& [kind, evaluation] : evaluations)
      out << "  oracle:   [" << output_kind_name(kind) << "] " << evaluation->oracle().plan_line
          << ", " << std::fixed << std::setprecision(1) << evaluation->oracle().time_ms << " ms\n"
          << std::defaultfloat;
    for (const PlannedRun& p : planned)
      out << "  run:      " << p.algorithm->info().id << ":" << p.variant << " ["
          << p.algorithm->info().backend << "]\n";
    for (const std::string& why : summary.left_out) out << "  left out: " << why << "\n";

    for (const PlannedRun& p : planned) {
      const AlgorithmInfo& meta = p.algorithm->info();
      RunRecord record = new_record(c, selectors[case_index], *p.algorithm, p.variant);
      progress.show(step + meta.id + ":" + p.variant + " [" + meta.backend + "]");
      const Case& view = record.output == OutputKind::hard_shadow ? hard_case : c;
      try {
        const std::vector<std::string> declared = p.algorithm->timed_phases(p.variant);
        for (const std::string& name : declared) record.phases.push_back({name, {}, 0});
        // An untimed warm-up run gives the output that is judged; the timed repeats after it
        // must reproduce it exactly. Phases are timed inside run(), so within each repeat.
        const AlgorithmOutput first = p.algorithm->run(view, samples, p.variant);
        check_phases(declared, first);
        for (std::uint32_t r = 0; r < c.parameters.repeats; ++r) {
          const auto start = Clock::now();
          const AlgorithmOutput again = p.algorithm->run(view, samples, p.variant);
          record.run_ms.push_back(elapsed_ms(start));
          check_phases(declared, again);
          for (std::size_t k = 0; k < declared.size(); ++k)
            record.phases[k].run_ms.push_back(again.phase_ms[k].second);
          if (record.verdict != Verdict::fail && !same_results(again, first)) {
            record.verdict = Verdict::fail;
            record.reason = "nondeterministic: timed repeat " + std::to_string(r + 1) +
                            " differs from the warm-up run";
          }
        }
        record.median_ms = median(record.run_ms);
        for (PhaseRuns& phase : record.phases) phase.median_ms = median(phase.run_ms);
        record.counters = first.counters;
        evaluations.at(record.output)->judge(first, record);
        for (const auto& [name, per_sample] : first.per_sample_counters)
          record.images.push_back(
              write_counter_heat_map(out_dir, record, samples, name, per_sample));
      } catch (const std::exception& e) {
        record.verdict = Verdict::crash;
        record.reason = std::string("exception: ") + e.what();
      }
      out << "  " << std::left << std::setw(15) << verdict_name(record.verdict) << std::right
          << record.test_name << "  " << std::fixed << std::setprecision(2) << record.median_ms
          << " ms" << phases_text(record) << "  " << std::defaultfloat << record.reason << "\n";
      records.push_back(std::move(record));
    }
    out << std::flush;
    summaries.push_back(std::move(summary));
  }

  const MachineInfo machine = machine_info();
  write_results_json(out_dir / "results.json", summaries, records, threads, machine);
  write_junit_xml(out_dir / "junit.xml", records);
  write_html_report({out_dir}, out_dir / "report.html");  // reads results.json back
  print_summary(out, records, machine, threads);
  out << "wrote " << (out_dir / "report.html").string() << ", "
      << (out_dir / "results.json").string() << ", " << (out_dir / "junit.xml").string()
      << " and images under " << (out_dir / "images").string() << "\n";

  const bool any_failure = std::any_of(records.begin(), records.end(), [](const RunRecord& r) {
    return r.verdict == Verdict::fail || r.verdict == Verdict::crash;
  });
  return any_failure ? exit_conformance_failure : exit_pass;
}

}  // namespace shadowcts
