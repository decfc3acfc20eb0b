#include "shadowcts/runner.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <ostream>
#include <sstream>

#include <tbb/global_control.h>
#include <tbb/info.h>

#include "hard_shadow_images.h"
#include "junit_xml.h"
#include "results_json.h"
#include "run_record.h"
#include "shadowcts/case_manifest.h"
#include "shadowcts/errors.h"
#include "shadowcts/fixtures.h"
#include "shadowcts/gbuffer_exr.h"
#include "shadowcts/hard_shadow_oracle.h"
#include "shadowcts/registry.h"

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

// Above this many caster triangles the automatic choice is the fast oracle: the exact oracle's
// AABB tree and exact predicates then cost more memory and time than a CI run should spend.
constexpr std::uint64_t exact_oracle_triangle_limit = 4'000'000;

std::vector<Case> load_cases(const RunOptions& options) {
  std::vector<Case> cases;
  std::vector<std::string> fixtures = options.fixtures;
  if (fixtures.empty() && options.case_files.empty()) fixtures = default_fixtures();
  for (const std::string& name : fixtures) cases.push_back(make_fixture(name));
  for (const std::string& file : options.case_files) cases.push_back(load_case_manifest(file));
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

// Hard-shadow algorithms see a sun disk as its centre direction: a directional light.
Case hard_shadow_view(const Case& c) {
  Case view = c;
  if (view.light && view.light->kind == ShadowLightKind::sun_disk) {
    view.light->kind = ShadowLightKind::directional;
    view.light->angular_radius = 0.0f;
  }
  return view;
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

std::string record_name(OutputKind output, const AlgorithmInfo& meta, const std::string& variant,
                        const std::string& case_name) {
  return output_kind_name(output) + "." + meta.id + "." + variant + "." + meta.backend + "." +
         case_name;
}

void print_summary(std::ostream& out, const std::vector<RunRecord>& records) {
  out << "\nsummary\n";
  out << std::left << std::setw(26) << "case" << std::setw(30) << "algorithm" << std::setw(15)
      << "verdict" << std::right << std::setw(11) << "median ms" << std::setw(10) << "leaks"
      << std::setw(10) << "false sh." << std::setw(11) << "ambiguous"
      << "\n";
  for (const RunRecord& r : records) {
    out << std::left << std::setw(26) << r.case_name << std::setw(30)
        << (r.algorithm + ":" + r.variant + " [" + r.backend + "]") << std::setw(15)
        << verdict_name(r.verdict) << std::right;
    if (r.verdict == Verdict::not_supported || r.verdict == Verdict::crash) {
      out << "\n";
      continue;
    }
    out << std::setw(11) << std::fixed << std::setprecision(2) << r.median_ms;
    if (r.hard)
      out << std::setw(10) << r.hard->leaks << std::setw(10) << r.hard->false_shadows
          << std::setw(11) << r.hard->ambiguous;
    out << "\n";
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
  const std::vector<Case> cases = load_cases(options);  // all input is checked before any work

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
    std::vector<PlannedRun> planned;
    const Case hard_case = hard_shadow_view(c);
    bool any_hard = false;
    for (const auto& a : registry.algorithms()) {
      const AlgorithmInfo& meta = a->info();
      for (const std::string& variant : meta.variants) {
        if (!selected(options, meta, variant)) continue;
        const Case& view = meta.capabilities.output == OutputKind::hard_shadow ? hard_case : c;
        RunRecord record;
        record.case_name = c.name;
        record.algorithm = meta.id;
        record.variant = variant;
        record.backend = meta.backend;
        record.output = meta.capabilities.output;
        record.test_name = record_name(meta.capabilities.output, meta, variant, c.name);
        if (auto why = a->unsupported_reason(view, samples, variant)) {
          record.verdict = Verdict::not_supported;
          record.reason = *why;
          summary.left_out.push_back(meta.id + ":" + variant + " [" + meta.backend + "]: " + *why);
          records.push_back(std::move(record));
          continue;
        }
        if (meta.capabilities.output != OutputKind::hard_shadow) {
          // Never a verdict without a comparison.
          record.verdict = Verdict::not_supported;
          record.reason = "the runner has no oracle comparison for " +
                          output_kind_name(meta.capabilities.output) + " outputs yet";
          summary.left_out.push_back(meta.id + ":" + variant + " [" + meta.backend +
                                     "]: " + record.reason);
          records.push_back(std::move(record));
          continue;
        }
        any_hard = true;
        planned.push_back({a.get(), variant});
      }
    }
    if (c.light && c.light->kind == ShadowLightKind::sun_disk)
      summary.left_out.push_back(
          "soft-shadow comparison: no registered algorithm computes sun-disk visibility yet; hard "
          "shadows use the disk's centre direction");
    if (!c.light) summary.left_out.push_back("hard-shadow oracle: the case has no shadow light");
    if (c.ranged_lights.empty())
      summary.left_out.push_back("light-assignment oracle: the case has no ranged lights");
    else
      summary.left_out.push_back(
          "light-assignment comparison: no registered algorithm assigns ranged lights yet");

    // The oracle, only when something needs it.
    HardShadowTruth truth;
    if (any_hard) {
      const bool use_exact = options.oracle == OracleChoice::exact ||
                             (options.oracle == OracleChoice::automatic &&
                              c.triangles.size() <= exact_oracle_triangle_limit);
      progress.show(step + (use_exact ? "exact oracle" : "Embree oracle"));
      const auto start = Clock::now();
      truth = use_exact ? exact_hard_shadow_oracle(hard_case, samples)
                        : embree_hard_shadow_oracle(hard_case, samples);
      summary.oracle_ms = elapsed_ms(start);
      summary.oracle_method = truth.method;
      summary.oracle_exact = truth.exact;
      summary.eps_rel = truth.eps_rel;
      summary.tau = truth.tau;
      if (!use_exact)
        summary.left_out.push_back("exact oracle: " + std::to_string(c.triangles.size()) +
                                   " triangles exceed its limit of " +
                                   std::to_string(exact_oracle_triangle_limit) +
                                   " (or --oracle embree); the fast oracle's band is estimated");
      for (BandClass b : truth.band) {
        summary.robust_lit += b == BandClass::robust_lit;
        summary.robust_shadowed += b == BandClass::robust_shadowed;
        summary.ambiguous += b == BandClass::ambiguous;
      }
      summary.oracle_image = write_oracle_images(out_dir, c.name, samples, truth);
    }

    out << "case " << c.name << "  (" << summary.triangles << " triangles, " << summary.width << "x"
        << summary.height << " samples: " << summary.regular << " regular, " << summary.sky
        << " sky, " << summary.back_facing << " back-facing; light " << summary.light;
    if (summary.ranged_lights) out << ", " << summary.ranged_lights << " ranged lights";
    out << ")\n";
    if (any_hard)
      out << "  oracle:   " << summary.oracle_method << ", eps_rel " << summary.eps_rel << " (tau "
          << summary.tau << "): " << summary.robust_lit << " robust-lit, "
          << summary.robust_shadowed << " robust-shadowed, " << summary.ambiguous << " ambiguous, "
          << std::fixed << std::setprecision(1) << summary.oracle_ms << " ms\n"
          << std::defaultfloat;
    for (const PlannedRun& p : planned)
      out << "  run:      " << p.algorithm->info().id << ":" << p.variant << " ["
          << p.algorithm->info().backend << "]\n";
    for (const std::string& why : summary.left_out) out << "  left out: " << why << "\n";

    for (const PlannedRun& p : planned) {
      const AlgorithmInfo& meta = p.algorithm->info();
      RunRecord record;
      record.case_name = c.name;
      record.algorithm = meta.id;
      record.variant = p.variant;
      record.backend = meta.backend;
      record.output = meta.capabilities.output;
      record.test_name = record_name(meta.capabilities.output, meta, p.variant, c.name);
      progress.show(step + meta.id + ":" + p.variant + " [" + meta.backend + "]");
      const Case& view = meta.capabilities.output == OutputKind::hard_shadow ? hard_case : c;
      try {
        AlgorithmOutput first;
        for (std::uint32_t r = 0; r < c.parameters.repeats; ++r) {
          const auto start = Clock::now();
          AlgorithmOutput result = p.algorithm->run(view, samples, p.variant);
          record.run_ms.push_back(elapsed_ms(start));
          if (r == 0) {
            first = std::move(result);
          } else if (result.shadowed != first.shadowed ||
                     result.visible_fraction != first.visible_fraction) {
            record.verdict = Verdict::fail;
            record.reason =
                "nondeterministic: repeat " + std::to_string(r + 1) + " differs from the first run";
          }
        }
        record.median_ms = median(record.run_ms);
        record.counters = first.counters;
        if (record.output == OutputKind::hard_shadow) {
          HardShadowComparison comparison = compare_hard_shadows(first.shadowed, truth);
          if (record.verdict != Verdict::fail) {
            record.verdict = comparison.verdict;
            record.reason = comparison.reason;
          }
          record.hard = std::move(comparison);
          record.images =
              write_algorithm_images(out_dir, c.name, record, samples, first.shadowed, truth);
        }
      } catch (const std::exception& e) {
        record.verdict = Verdict::crash;
        record.reason = std::string("exception: ") + e.what();
      }
      out << "  " << std::left << std::setw(15) << verdict_name(record.verdict) << std::right
          << record.test_name << "  " << std::fixed << std::setprecision(2) << record.median_ms
          << " ms  " << std::defaultfloat << record.reason << "\n";
      records.push_back(std::move(record));
    }
    out << std::flush;
    summaries.push_back(std::move(summary));
  }

  write_results_json(out_dir / "results.json", summaries, records, threads);
  write_junit_xml(out_dir / "junit.xml", records);
  print_summary(out, records);
  out << "wrote " << (out_dir / "results.json").string() << ", " << (out_dir / "junit.xml").string()
      << " and images under " << (out_dir / "images").string() << "\n";

  const bool any_failure = std::any_of(records.begin(), records.end(), [](const RunRecord& r) {
    return r.verdict == Verdict::fail || r.verdict == Verdict::crash;
  });
  return any_failure ? exit_conformance_failure : exit_pass;
}

}  // namespace shadowcts
