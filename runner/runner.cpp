#include "shadowcts/runner.h"

#include <fcntl.h>  // AT_FDCWD; renameat2 and RENAME_EXCHANGE come with <cstdio> (glibc)
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <ostream>
#include <set>
#include <sstream>
#include <system_error>
#include <thread>

#include <tbb/global_control.h>
#include <tbb/info.h>

#include "case_evaluation.h"
#include "case_gbuffer.h"
#include "hard_shadow_evaluation.h"
#include "heat_map.h"
#include "image_paths.h"
#include "interrupt_cleanup.h"
#include "junit_xml.h"
#include "known_limits.h"
#include "light_assignment_evaluation.h"
#include "machine_info.h"
#include "named_case.h"
#include "report/html_report.h"
#include "results_json.h"
#include "run_record.h"
#include "shadowcts/case_manifest.h"
#include "shadowcts/errors.h"
#include "shadowcts/fixtures.h"
#include "shadowcts/hard_shadow_inputs.h"
#include "shadowcts/phase_progress.h"
#include "shadowcts/registry.h"
#include "soft_shadow_evaluation.h"
#include "truth_cache.h"

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
// `gbuffer_formats[i]`: how case i's G-buffer is laid out (manifests only).
// `given_samples[i]`: case i's view samples where its fixture places them itself (the fuzz cases
// `fuzz.<generator>.<seed>.<index>`, fixtures/fuzz/fuzz_fixtures.h), and `case_limits[i]` the
// limits of peers that its generator declares.
std::vector<Case> load_cases(const RunOptions& options, std::vector<std::string>& selectors,
                             std::vector<GBufferFormat>& gbuffer_formats,
                             std::vector<std::optional<ViewSamples>>& given_samples,
                             std::vector<std::vector<fuzzing::KnownLimit>>& case_limits) {
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
      NamedCase named = make_named_case(name);
      cases.push_back(std::move(named.c));
      given_samples.push_back(std::move(named.samples));
      case_limits.push_back(std::move(named.known_limits));
      selectors.push_back("--fixture " + name);
      gbuffer_formats.emplace_back();
    }
  for (const std::string& file : options.case_files)
    if (in_shard()) {
      gbuffer_formats.emplace_back();
      given_samples.emplace_back();
      case_limits.emplace_back();
      cases.push_back(load_case_manifest(file, gbuffer_formats.back()));
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

bool on_selected_backend(const RunOptions& options, const AlgorithmInfo& meta) {
  return options.backends.empty() ||
         std::count(options.backends.begin(), options.backends.end(), meta.backend) != 0;
}

// " --backend a --backend b" as the user gave them, for messages.
std::string backend_flags(const RunOptions& options) {
  std::string flags;
  for (const std::string& backend : options.backends) flags += " --backend " + backend;
  return flags;
}

bool selected(const RunOptions& options, const AlgorithmInfo& meta, const std::string& variant) {
  if (!on_selected_backend(options, meta)) return false;
  if (options.algorithms.empty()) return true;
  for (const AlgorithmSelection& s : options.algorithms)
    if (s.id == meta.id && (s.variant.empty() || s.variant == variant)) return true;
  return false;
}

std::string comma_list(const std::set<std::string>& names) {
  std::string out;
  for (const std::string& name : names) out += (out.empty() ? "" : ", ") + name;
  return out;
}

void check_selection(const RunOptions& options, const Registry& registry) {
  std::set<std::string> backends, ids;
  for (const auto& a : registry.algorithms()) {
    backends.insert(a->info().backend);
    ids.insert(a->info().id);
  }
  for (const std::string& backend : options.backends)
    if (!backends.count(backend))
      throw UsageError("--backend " + backend +
                       ": unknown backend (known: " + comma_list(backends) + ")");
  for (const AlgorithmSelection& s : options.algorithms) {
    bool found = false;
    std::set<std::string> variants;  // of s.id on the selected backends, for the message
    for (const auto& a : registry.algorithms()) {
      const AlgorithmInfo& meta = a->info();
      if (meta.id != s.id) continue;
      if (!on_selected_backend(options, meta)) continue;
      variants.insert(meta.variants.begin(), meta.variants.end());
      if (s.variant.empty() || std::count(meta.variants.begin(), meta.variants.end(), s.variant))
        found = true;
    }
    if (!found)
      throw UsageError("--algorithm " + s.id + (s.variant.empty() ? "" : ":" + s.variant) +
                       backend_flags(options) + ": no such registered algorithm (" +
                       (!ids.count(s.id)   ? "known: " + comma_list(ids)
                        : variants.empty() ? "not on this backend"
                                           : "variants of " + s.id + ": " + comma_list(variants)) +
                       "; see `shadowcts list`)");
  }
  // Each selector exists, but together they may still select nothing (an algorithm on another
  // backend): a run of nothing would be a green CI job that tested nothing.
  bool any = false;
  for (const auto& a : registry.algorithms())
    for (const std::string& variant : a->info().variants)
      any |= selected(options, a->info(), variant);
  if (!any)
    throw UsageError(
        "the selection (--algorithm/--backend) matches no registered algorithm "
        "variant (see `shadowcts list`)");
}

// The names a run writes into its folder (and their temporaries): only a folder holding nothing
// else is taken for a previous run and replaced.
bool run_output_name(const std::string& name) {
  for (const char* own : {"results.json", "junit.xml", "report.html", "images"})
    if (name == own || name == std::string(own) + ".partial") return true;
  return false;
}

// --out, checked before anything is written: where the run's folder will be. An existing folder
// must be empty or hold a previous run, which the finished run replaces.
std::filesystem::path checked_out_dir(const std::string& text) {
  namespace fs = std::filesystem;
  if (text.empty()) throw UsageError("--out '': give a folder name (e.g. --out shadowcts-out)");
  fs::path dir = fs::absolute(fs::path(text)).lexically_normal();
  if (!dir.has_filename()) dir = dir.parent_path();  // "out/" -> "out"
  std::error_code ec;
  if (fs::is_symlink(fs::symlink_status(dir, ec))) {
    dir = fs::canonical(dir, ec);  // replace the folder, not the link
    if (ec) throw UsageError("--out " + text + ": " + ec.message());
  }
  // The folder is replaced as a whole: never the current folder or one holding it.
  const fs::path here = fs::current_path(ec);
  const bool holds_here =
      !ec && !here.lexically_relative(dir).empty() && *here.lexically_relative(dir).begin() != "..";
  if (dir == dir.root_path() || dir.filename() == "." || dir.filename() == ".." || holds_here)
    throw UsageError("--out " + text +
                     ": give a folder of its own for the run's outputs (it is replaced as a "
                     "whole), not the current folder or one above it");
  ec.clear();
  const fs::file_status status = fs::status(dir, ec);
  if (!fs::exists(status)) return dir;
  if (!fs::is_directory(status)) throw UsageError("--out " + text + ": exists and is not a folder");
  for (const fs::directory_entry& entry : fs::directory_iterator(dir, ec))
    if (!run_output_name(entry.path().filename().string()))
      throw UsageError("--out " + text + ": the folder holds '" + entry.path().filename().string() +
                       "', which is not part of a shadowcts run; give an empty or new folder (a "
                       "previous run's folder is replaced when the new run is complete)");
  if (ec) throw UsageError("--out " + text + ": cannot read the folder: " + ec.message());
  return dir;
}

// The run is written into <out>.partial-<pid> beside <out> and swapped in when complete, so <out>
// always holds one whole run (the new one or the previous one), and a killed run leaves a folder
// whose name says it is unfinished. A run that fails with an exception, or is interrupted
// (interrupt_cleanup.h), removes its partial folder.
class StagedOutput {
 public:
  explicit StagedOutput(std::filesystem::path target) : target_(std::move(target)) {
    namespace fs = std::filesystem;
    const std::string pid = std::to_string(::getpid());
    staging_ = target_.parent_path() / (target_.filename().string() + ".partial-" + pid);
    old_ = target_.parent_path() / (target_.filename().string() + ".old-" + pid);
    unfinished_ = InterruptCleanup::remove_path(staging_);
    std::error_code ec;
    fs::remove_all(staging_, ec);  // a leftover of a killed run whose pid this one reuses
    fs::create_directories(staging_ / "images", ec);
    if (ec) throw OutputError(staging_.string(), "cannot create folder: " + ec.message());
  }
  StagedOutput(const StagedOutput&) = delete;
  StagedOutput& operator=(const StagedOutput&) = delete;
  ~StagedOutput() {
    std::error_code ignored;
    if (!committed_) std::filesystem::remove_all(staging_, ignored);
  }
  const std::filesystem::path& dir() const { return staging_; }

  // Puts the finished run at the target; the previous run there is removed. Returns false (and
  // says why on `err`) only when the previous run could not be removed.
  bool commit(std::ostream& err) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (!fs::exists(target_, ec)) {
      fs::rename(staging_, target_, ec);
      if (ec)
        throw OutputError(target_.string(), "cannot move the run into place: " + ec.message());
      committed_ = true;
      return true;
    }
    // One atomic exchange where the file system has it: no moment without a whole run there.
    fs::path previous = staging_;
    if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, target_.c_str(), RENAME_EXCHANGE) != 0) {
      const int error = errno;
      if (error != EINVAL && error != ENOSYS)
        throw OutputError(target_.string(), "cannot swap the run into place: " +
                                                std::generic_category().message(error));
      // Two renames otherwise; a kill between them leaves <out>.old-<pid> and <out>.partial-<pid>.
      previous = old_;
      fs::rename(target_, old_, ec);
      if (ec)
        throw OutputError(target_.string(), "cannot move the previous run aside: " + ec.message());
      fs::rename(staging_, target_, ec);
      if (ec)
        throw OutputError(target_.string(), "cannot move the run into place: " + ec.message());
    }
    committed_ = true;
    fs::remove_all(previous, ec);
    if (ec) {
      err << "shadowcts: warning: cannot remove the previous run at " << previous.string() << ": "
          << ec.message() << "\n";
      return false;
    }
    return true;
  }

 private:
  std::filesystem::path target_, staging_, old_;
  bool committed_ = false;
  std::optional<InterruptCleanup> unfinished_;
};

// The current step and how far its phase is (phase_progress.h): on a terminal a line redrawn
// four times a second with done / total and an ETA; otherwise, for CI logs, a plain line once a
// minute while a step runs (short steps print nothing).
class Progress {
 public:
  Progress(bool terminal, bool plain_lines, double plain_interval_s, std::ostream& err)
      : terminal_(terminal),
        plain_lines_(plain_lines && !terminal),
        plain_interval_(std::chrono::duration<double>(plain_interval_s)),
        err_(err) {
    if (terminal_ || plain_lines_) reporter_ = std::thread([this] { report(); });
  }
  void show(const std::string& step) {
    phase_progress::begin(0);  // a phase that reports calls begin() with its total
    std::lock_guard<std::mutex> lock(mutex_);
    step_ = step;
    step_start_ = std::chrono::steady_clock::now();
    last_plain_ = step_start_;
    if (terminal_) err_ << "\r\033[K" << step_ << std::flush;
  }
  // The next run of the same step (the warm-up, then each timed repeat): the line names it, and
  // its phases begin anew; the step's elapsed time and the plain lines' rhythm go on.
  void show_run(const std::string& step) {
    phase_progress::begin(0);
    std::lock_guard<std::mutex> lock(mutex_);
    step_ = step;
  }
  ~Progress() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    if (reporter_.joinable()) reporter_.join();
    if (terminal_) err_ << "\r\033[K" << std::flush;
  }

 private:
  static std::string duration_text(double seconds) {
    const long s = std::lround(seconds);
    std::ostringstream out;
    if (s >= 60)
      out << s / 60 << " min " << std::setw(2) << std::setfill('0') << s % 60 << " s";
    else
      out << s << " s";
    return out.str();
  }

  // Notes when a new phase began (seen at every wake-up, a quarter second at most after it did):
  // a step may run several phases (one per emulated kernel launch), and the ETA is the current
  // phase's, from its own rate.
  phase_progress::Snapshot observe(std::chrono::steady_clock::time_point now) {
    const phase_progress::Snapshot p = phase_progress::snapshot();
    if (p.generation != phase_generation_) {
      phase_generation_ = p.generation;
      phase_start_ = now;
      phase_start_done_ = p.done;
    }
    return p;
  }

  // The step's elapsed time, the phase's done / total and the ETA of the phase.
  std::string status_line(std::chrono::steady_clock::time_point now,
                          const phase_progress::Snapshot& p) const {
    const double elapsed = std::chrono::duration<double>(now - step_start_).count();
    const double phase_elapsed = std::chrono::duration<double>(now - phase_start_).count();
    std::ostringstream line;
    line << step_ << " — ";
    if (p.total > 0) {
      const double fraction = std::min(1.0, double(p.done) / double(p.total));
      line << p.done << " / " << p.total;
      if (*p.unit != '\0') line << " " << p.unit;
      if (*p.of != '\0') line << " of " << p.of;
      line << " (" << std::fixed << std::setprecision(1) << 100.0 * fraction << " %), "
           << duration_text(elapsed);
      const std::uint64_t since = p.done > phase_start_done_ ? p.done - phase_start_done_ : 0;
      if (since > 0 && p.done < p.total && phase_elapsed > 0.0)
        line << ", ETA " << duration_text(phase_elapsed * double(p.total - p.done) / double(since));
    } else {
      line << duration_text(elapsed);
    }
    return line.str();
  }

  void report() {
    std::unique_lock<std::mutex> lock(mutex_);
    while (!stop_) {
      wake_.wait_for(lock, std::min<std::chrono::duration<double>>(std::chrono::milliseconds(250),
                                                                   plain_interval_));
      if (stop_ || step_.empty()) continue;
      const auto now = std::chrono::steady_clock::now();
      const phase_progress::Snapshot p = observe(now);
      if (terminal_ && now - step_start_ > std::chrono::milliseconds(500)) {
        err_ << "\r\033[K" << status_line(now, p) << std::flush;
      } else if (plain_lines_ && now - last_plain_ >= plain_interval_) {
        err_ << "progress: " << status_line(now, p) << "\n" << std::flush;
        last_plain_ = now;
      }
    }
  }

  const bool terminal_, plain_lines_;
  const std::chrono::duration<double> plain_interval_;
  std::ostream& err_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::string step_;
  std::chrono::steady_clock::time_point step_start_{}, last_plain_{}, phase_start_{};
  std::uint64_t phase_generation_ = 0, phase_start_done_ = 0;
  std::thread reporter_;
};

RunRecord new_record(const Case& c, const std::string& selector, const std::string& image_folder,
                     const Algorithm& algorithm, const std::string& variant) {
  const AlgorithmInfo& meta = algorithm.info();
  RunRecord record;
  record.case_name = c.name;
  record.image_folder = image_folder;
  record.algorithm = meta.id;
  record.variant = variant;
  record.backend = meta.backend;
  record.output = meta.capabilities.output;
  record.approximate = meta.capabilities.approximate;
  if (record.approximate) record.mismatch_ceiling = algorithm.robust_mismatch_ceiling(variant);
  if (record.output == OutputKind::soft_shadow)
    record.soft_budget = algorithm.soft_error_budget(variant);
  // An engine's result (shadowcts check) is not in any registry: its manifest reruns it.
  record.reproduce = meta.backend == "external"
                         ? "shadowcts check " + selector
                         : "shadowcts run " + selector + " --algorithm " + meta.id + ":" + variant +
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
  if (r.phases.empty() || r.run_ms.empty() || did_not_finish(r.verdict)) return "";
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
                                         const std::vector<std::uint8_t>& receiver_ambiguous,
                                         OracleChoice choice, const ImageTarget& images,
                                         const std::string& image_folder,
                                         std::vector<std::string>& left_out,
                                         const TruthCache* cache) {
  switch (kind) {
    case OutputKind::hard_shadow:
      return evaluate_hard_shadows(c, samples, receiver_ambiguous, choice, images, image_folder,
                                   left_out, cache);
    case OutputKind::soft_shadow:
      return evaluate_soft_shadows(c, samples, receiver_ambiguous, choice, images, image_folder,
                                   left_out, cache);
    case OutputKind::light_lists:
      return evaluate_light_assignment(c, samples, images, image_folder, cache);
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
    // The plan's "left out" lines say why; one that ran had nothing to judge: say so here too.
    if (r.verdict == Verdict::not_supported && r.run_ms.empty()) continue;
    out << std::left << std::setw(34) << r.case_name << std::setw(38)
        << (r.algorithm + ":" + r.variant + " [" + r.backend + "]") << std::setw(15)
        << verdict_name(r.verdict) << std::right;
    if (did_not_finish(r.verdict)) {
      out << "   " << r.reason << "\n";
      continue;
    }
    out << std::setw(11) << std::fixed << std::setprecision(2) << r.median_ms << "   " << r.headline
        << phases_text(r) << "\n";
  }
  std::size_t counts[6] = {};
  for (const RunRecord& r : records) ++counts[int(r.verdict)];
  out << "\n"
      << records.size() << " results: " << counts[int(Verdict::pass)] << " Pass, "
      << counts[int(Verdict::fail)] << " Fail, " << counts[int(Verdict::quality_warning)]
      << " QualityWarning, " << counts[int(Verdict::not_supported)] << " NotSupported, "
      << counts[int(Verdict::crash)] << " Crash"
      << (counts[int(Verdict::timeout)]
              ? ", " + std::to_string(counts[int(Verdict::timeout)]) + " Timeout"
              : std::string())
      << "\n";
  const auto limited = std::count_if(records.begin(), records.end(),
                                     [](const RunRecord& r) { return !r.known_limit.empty(); });
  if (limited)
    out << "of the Fails, " << limited << (limited == 1 ? " is a known limit" : " are known limits")
        << " of its method (\"a known limit\" under the record; docs/specification.md)\n";
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
  // Every input is checked before the output folder is touched: options, every case, every
  // G-buffer.
  check_selection(options, registry);
  const std::filesystem::path target = checked_out_dir(options.out_dir);
  std::vector<std::string> selectors;
  std::vector<GBufferFormat> gbuffer_formats;
  std::vector<std::optional<ViewSamples>> given_samples;
  std::vector<std::vector<fuzzing::KnownLimit>> case_limits;
  const std::vector<Case> cases =
      load_cases(options, selectors, gbuffer_formats, given_samples, case_limits);
  if (cases.empty())
    throw UsageError("the selection matches no case" +
                     (options.shard_count > 1 ? " in shard " + std::to_string(options.shard_index) +
                                                    "/" + std::to_string(options.shard_count)
                                              : std::string()));
  // G-buffers are read now and kept until their case runs: a bad one must fail the run before
  // any case has written anything.
  std::vector<std::optional<CaseGBuffer>> gbuffers(cases.size());
  for (std::size_t i = 0; i < cases.size(); ++i)
    if (!cases[i].gbuffer_path.empty())
      gbuffers[i] = load_case_gbuffer(cases[i], gbuffer_formats[i]);
  std::vector<std::string> case_names;
  for (const Case& c : cases) case_names.push_back(c.name);
  const std::vector<std::string> image_folders = case_image_folders(case_names);

  const std::uint32_t threads = options.threads.value_or(0)
                                    ? *options.threads
                                    : std::uint32_t(tbb::info::default_concurrency());
  tbb::global_control thread_limit(tbb::global_control::max_allowed_parallelism, threads);

  std::optional<TruthCache> truth_cache;
  if (!options.truth_cache_dir.empty()) truth_cache.emplace(options.truth_cache_dir);

  StagedOutput staged(target);
  const std::filesystem::path& out_dir = staged.dir();
  const ImageTarget images{out_dir, options.images};

  Progress progress(options.progress, options.progress_lines, options.progress_line_seconds, err);
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
    std::vector<std::uint8_t> receiver_ambiguous;
    std::string receivers_line;
    if (given_samples[case_index]) {
      samples = std::move(*given_samples[case_index]);
      given_samples[case_index].reset();
      summary.samples_from = "the fuzz generator";
      summary.left_out.push_back("Embree G-buffer pass: the fuzz generator places the samples");
    } else if (c.gbuffer_path.empty()) {
      samples = generate_view_samples(c);
      summary.samples_from = "embree primary rays";
    } else {
      CaseGBuffer& gbuffer = *gbuffers[case_index];
      if (gbuffer.receivers_searched) {
        receivers_line = receiver_plan_line(gbuffer);
        summary.receivers = {{"from", "search"},
                             {"tau", gbuffer.tau},
                             {"unique", gbuffer.unique_receivers},
                             {"ambiguous", gbuffer.ambiguous_receivers}};
      }
      samples = std::move(gbuffer.samples);
      receiver_ambiguous = std::move(gbuffer.receiver_ambiguous);
      gbuffers[case_index].reset();
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
          RunRecord record =
              new_record(c, selectors[case_index], image_folders[case_index], *a, variant);
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
    if (!options.images) summary.left_out.push_back("images (PNG/EXR): --no-images asked for none");

    // Oracles, only for the output kinds that something planned needs.
    std::map<OutputKind, std::unique_ptr<CaseEvaluation>> evaluations;
    for (OutputKind kind : kinds) {
      progress.show(step + output_kind_name(kind) + " oracle");
      evaluations[kind] =
          evaluate(kind, kind == OutputKind::hard_shadow ? hard_case : c, samples,
                   receiver_ambiguous, options.oracle, images, image_folders[case_index],
                   summary.left_out, truth_cache ? &*truth_cache : nullptr);
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
    if (!receivers_line.empty()) out << "  receivers: " << receivers_line << "\n";
    for (const auto& [kind, evaluation] : evaluations)
      out << "  oracle:   [" << output_kind_name(kind) << "] " << evaluation->oracle().plan_line
          << ", " << std::fixed << std::setprecision(1) << evaluation->oracle().time_ms << " ms\n"
          << std::defaultfloat;
    for (const PlannedRun& p : planned)
      out << "  run:      " << p.algorithm->info().id << ":" << p.variant << " ["
          << p.algorithm->info().backend << "]\n";
    for (const std::string& why : summary.left_out) out << "  left out: " << why << "\n";
    out << std::flush;  // stdout may be a pipe or a CI log: show the plan before the runs

    // One prepared scene per case view, built once and read by every algorithm.
    std::optional<PreparedScene> hard_scene, full_scene;
    for (const PlannedRun& p : planned) {
      if (p.algorithm->info().capabilities.output == OutputKind::hard_shadow) {
        if (!hard_scene) hard_scene.emplace(prepare_scene(hard_case, samples));
      } else if (!full_scene) {
        full_scene.emplace(prepare_scene(c, samples));
      }
    }

    for (const PlannedRun& p : planned) {
      const AlgorithmInfo& meta = p.algorithm->info();
      RunRecord record =
          new_record(c, selectors[case_index], image_folders[case_index], *p.algorithm, p.variant);
      const std::string algorithm_step =
          step + meta.id + ":" + p.variant + " [" + meta.backend + "]";
      progress.show(algorithm_step);
      // An emulated backend's time is the emulator's, not a GPU's, and there is no GPU to warm:
      // unless --repeat asks for timed repeats, it runs once, and that run is judged and timed.
      const bool run_once = meta.emulated && !options.repeats;
      const std::uint32_t repeats = run_once ? 1 : c.parameters.repeats;
      const std::uint32_t runs = repeats + (run_once ? 0 : 1);
      const auto run_step = [&](std::uint32_t run) {
        return algorithm_step + ", run " + std::to_string(run) + " of " + std::to_string(runs);
      };
      const PreparedScene& scene =
          record.output == OutputKind::hard_shadow ? *hard_scene : *full_scene;
      try {
        const std::vector<std::string> declared = p.algorithm->timed_phases(p.variant);
        for (const std::string& name : declared) record.phases.push_back({name, {}, 0});
        // Otherwise an untimed warm-up run gives the output that is judged, and the timed
        // repeats after it must reproduce it exactly. Phases are timed inside run().
        std::optional<AlgorithmOutput> first;
        if (!run_once) {
          if (runs > 1) progress.show_run(run_step(1));
          first = p.algorithm->run(scene, p.variant);
          check_phases(declared, *first);
        }
        for (std::uint32_t r = 0; r < repeats; ++r) {
          if (runs > 1) progress.show_run(run_step(runs - repeats + r + 1));
          const auto start = Clock::now();
          AlgorithmOutput again = p.algorithm->run(scene, p.variant);
          record.run_ms.push_back(elapsed_ms(start));
          check_phases(declared, again);
          for (std::size_t k = 0; k < declared.size(); ++k)
            record.phases[k].run_ms.push_back(again.phase_ms[k].second);
          if (!first) {
            first = std::move(again);
          } else if (record.verdict != Verdict::fail && !same_results(again, *first)) {
            record.verdict = Verdict::fail;
            record.reason = "nondeterministic: timed repeat " + std::to_string(r + 1) +
                            " differs from the warm-up run";
          }
        }
        record.median_ms = median(record.run_ms);
        for (PhaseRuns& phase : record.phases) phase.median_ms = median(phase.run_ms);
        record.counters = first->counters;
        const CaseEvaluation& evaluation = *evaluations.at(record.output);
        const bool nondeterministic = record.verdict == Verdict::fail;
        evaluation.judge(*first, record);
        if (record.verdict == Verdict::fail && !nondeterministic)
          record.known_limit =
              known_limit(record.test_name, record.algorithm, record.variant,
                          case_limits[case_index], evaluation.robust_mismatches(*first));
        if (images.enabled)
          for (const auto& [name, per_sample] : first->per_sample_counters)
            record.images.push_back(
                write_counter_heat_map(out_dir, record, samples, name, per_sample));
      } catch (const OutputError&) {
        throw;  // the tool's failure to write an image, not the algorithm's: exit 3
      } catch (const std::exception& e) {
        record.verdict = Verdict::crash;
        record.reason = std::string("exception: ") + e.what();
      }
      out << "  " << std::left << std::setw(15) << verdict_name(record.verdict) << std::right
          << record.test_name << "  " << std::fixed << std::setprecision(2) << record.median_ms
          << " ms" << phases_text(record) << "  " << std::defaultfloat << record.reason << "\n";
      if (!record.known_limit.empty()) out << "    a known limit: " << record.known_limit << "\n";
      out << std::flush;  // one line per record as it finishes, also when stdout is not a TTY
      records.push_back(std::move(record));
    }
    summaries.push_back(std::move(summary));
  }

  const MachineInfo machine = machine_info();
  write_results_json(out_dir / "results.json", summaries, records, threads, machine);
  write_junit_xml(out_dir / "junit.xml", records);
  write_html_report({out_dir}, out_dir / "report.html");  // reads results.json back
  staged.commit(err);
  print_summary(out, records, machine, threads);
  const std::filesystem::path shown(options.out_dir);  // as the user wrote it
  out << "wrote " << (shown / "report.html").string() << ", " << (shown / "results.json").string()
      << ", " << (shown / "junit.xml").string()
      << (options.images ? " and images under " + (shown / "images").string() : " (no images)")
      << "\n";

  const bool any_failure = std::any_of(records.begin(), records.end(), [](const RunRecord& r) {
    return r.verdict == Verdict::fail || did_not_finish(r.verdict);
  });
  return any_failure ? exit_conformance_failure : exit_pass;
}

}  // namespace shadowcts
