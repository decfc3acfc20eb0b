// shadowcts: conformance tests with reference oracles for shadow and light-assignment algorithms.
#include <unistd.h>

#include <charconv>
#include <cstdint>
#include <iostream>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/interrupt_cleanup.h"
#include "list_command.h"
#include "report_command.h"
#include "runner/certify.h"
#include "runner/external_result.h"
#include "runner/named_case.h"
#include "runner/scene_export.h"
#include "shadowcts/case_manifest.h"
#include "shadowcts/errors.h"
#include "shadowcts/gbuffer_exr.h"
#include "shadowcts/registry.h"
#include "shadowcts/runner.h"

namespace {

using namespace shadowcts;

AlgorithmSelection parse_selection(const std::string& text) {
  const auto colon = text.find(':');
  AlgorithmSelection s{text.substr(0, colon),
                       colon == std::string::npos ? "" : text.substr(colon + 1)};
  if (s.id.empty() || (colon != std::string::npos && s.variant.empty()))
    throw UsageError("--algorithm '" + text + "': expected ID or ID:VARIANT");
  return s;
}

// "I/N" with decimal digits only, 0 <= I < N <= 2^32 - 1; anything else (a sign, spaces, a value
// out of range, which sscanf's %u would wrap) is a usage error naming the value.
void parse_shard(const std::string& text, RunOptions& options) {
  const std::string usage = "--shard '" + text + "': ";
  const auto slash = text.find('/');
  if (slash == std::string::npos)
    throw UsageError(usage + "expected I/N (0-based shard I of N), e.g. 0/4");
  auto number = [&](std::string_view digits, const char* what) {
    if (digits.empty() || digits.find_first_not_of("0123456789") != std::string_view::npos)
      throw UsageError(usage + what + " must be a decimal number, is '" + std::string(digits) +
                       "'");
    std::uint64_t value = 0;
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (error != std::errc() || end != digits.data() + digits.size() ||
        value > std::numeric_limits<std::uint32_t>::max())
      throw UsageError(usage + what + " " + std::string(digits) + " is out of range (at most " +
                       std::to_string(std::numeric_limits<std::uint32_t>::max()) + ")");
    return std::uint32_t(value);
  };
  const std::string_view view(text);
  const std::uint32_t index = number(view.substr(0, slash), "I");
  const std::uint32_t count = number(view.substr(slash + 1), "N");
  if (count == 0) throw UsageError(usage + "N must be at least 1");
  if (index >= count) throw UsageError(usage + "I must be below N (shards are numbered 0 to N-1)");
  options.shard_index = index;
  options.shard_count = count;
}

// The case that `command`'s --case FILE or --fixture NAME names (exactly one of them).
NamedCase case_named_by(const std::string& command, const std::string& case_file,
                        const std::string& fixture) {
  if (case_file.empty() == fixture.empty())
    throw UsageError(command + ": give exactly one of --case FILE or --fixture NAME");
  if (!fixture.empty()) return make_named_case(fixture);
  return {load_case_manifest(case_file), std::nullopt, {}};
}

int write_gbuffer(const std::string& case_file, const std::string& fixture,
                  const std::string& out) {
  ViewSamples samples;
  NamedCase named = case_named_by("gbuffer", case_file, fixture);
  if (named.samples) {
    samples = std::move(*named.samples);  // a fuzz case's own; the camera is only its frame's size
  } else {
    validate(named.c);
    samples = generate_view_samples(named.c);
  }
  write_gbuffer_exr(out, samples);
  std::cout << "wrote " << out << ": " << samples.width << "x" << samples.height << ", "
            << samples.count(SampleClass::regular) + samples.count(SampleClass::back_facing)
            << " surface samples, " << samples.count(SampleClass::sky) << " sky\n";
  return exit_pass;
}

}  // namespace

int main(int argc, char** argv) {
  handle_interruptions();  // before any thread starts, so that every thread inherits it
  CLI::App app{
      "shadowcts: conformance tests with exact reference oracles for pixel-accurate shadow and "
      "light-assignment algorithms"};
  app.require_subcommand(1);

  bool list_json = false;
  CLI::App* list = app.add_subcommand("list", "List fixtures, algorithms, variants and backends");
  list->add_flag("--json", list_json, "Machine-readable output");

  RunOptions options;
  std::vector<std::string> algorithm_texts;
  double eps_rel = 0;
  std::uint32_t repeats = 0, threads = 0;
  std::string oracle = "auto";
  CLI::App* run = app.add_subcommand(
      "run", "Run algorithms on cases, diff them against the oracles, write results");
  run->add_option("--fixture", options.fixtures, "Built-in fixture (repeatable); see `list`");
  run->add_option("--suite", options.suite, "Named case suite: stiff (the numerical traps)")
      ->check(CLI::IsMember({"stiff"}));
  run->add_option("--case", options.case_files, "JSON case manifest (repeatable)")
      ->check(CLI::ExistingFile);
  run->add_option("--algorithm", algorithm_texts, "ID or ID:VARIANT (repeatable); default all");
  run->add_option("--backend", options.backends,
                  "Only these backends (reference, simd, embree, cuda, cuda-emu, ...); repeatable");
  run->add_option("--out", options.out_dir, "Output folder")->capture_default_str();
  // Not CLI::Range: it lets "nan" through (every comparison with NaN is false), and the case's
  // validation then blamed the manifest's parameters.eps_rel for the command line's value.
  auto* eps_option =
      run->add_option("--eps-rel", eps_rel,
                      "Relative half-width of the ambiguity band (default 2^-16)")
          ->check(CLI::Validator(
              [](std::string& text) {
                double value = 0;
                if (CLI::detail::lexical_cast(text, value) && value >= 0x1p-24 && value <= 0x1p-4)
                  return std::string();
                return "must be a number in [2^-24, 2^-4], is '" + text + "'";
              },
              "in [2^-24, 2^-4]"));
  auto* repeat_option = run->add_option("--repeat", repeats,
                                        "Timed repeats per algorithm after one warm-up run "
                                        "(default 2; emulated backends by default run once, "
                                        "without a warm-up; median and min-max reported)")
                            ->check(CLI::Range(1, 1000));
  auto* threads_option =
      run->add_option("--threads", threads, "Worker threads (default: all cores)")
          ->check(CLI::Range(1, 4096));
  std::string shard;
  run->add_option("--shard", shard, "Run only shard I of N (I/N, 0-based), for CI matrices");
  run->add_option("--oracle", oracle, "Hard-shadow oracle: auto, exact or embree")
      ->check(CLI::IsMember({"auto", "exact", "embree"}))
      ->capture_default_str();
  run->add_option("--truth-cache", options.truth_cache_dir,
                  "Keep oracle truths in this folder and reuse them for the same build and "
                  "inputs (repeated runs, ports judged on the same cases)");
  bool no_images = false;
  run->add_flag("--no-images", no_images,
                "Write no PNG/EXR images (CI gating on the verdicts; results and report as usual)");
  int progress_seconds = 60;
  run->add_option("--progress-seconds", progress_seconds,
                  "Seconds between the plain `progress:` lines written while a step runs when "
                  "stderr is no terminal (default 60)")
      ->check(CLI::Range(1, 3600));

  std::string gbuffer_case, gbuffer_fixture, gbuffer_out;
  CLI::App* gbuffer = app.add_subcommand(
      "gbuffer", "Write the view samples of a case as an EXR G-buffer (P, N, id channels)");
  gbuffer->add_option("--case", gbuffer_case, "JSON case manifest")->check(CLI::ExistingFile);
  gbuffer->add_option("--fixture", gbuffer_fixture, "Built-in fixture");
  gbuffer->add_option("--out", gbuffer_out, "Output EXR file")->required();

  std::string check_case, check_out = "shadowcts-check";
  CLI::App* check = app.add_subcommand(
      "check", "Judge an engine's own frame result (the manifest's \"result\") against the oracle");
  check->add_option("--case", check_case, "JSON case manifest with a \"result\"")
      ->required()
      ->check(CLI::ExistingFile);
  check->add_option("--out", check_out, "Output folder")->capture_default_str();

  std::string export_case_file, export_fixture, export_out;
  CLI::App* export_command = app.add_subcommand(
      "export", "Write a case for an engine: scene.glb, case.json and gbuffer.exr in a folder");
  export_command->add_option("--case", export_case_file, "JSON case manifest")
      ->check(CLI::ExistingFile);
  export_command->add_option("--fixture", export_fixture, "Built-in fixture");
  export_command->add_option("--out", export_out, "Output folder (new or empty)")->required();

  std::vector<std::string> report_dirs;
  std::string report_out;
  CLI::App* report = app.add_subcommand(
      "report", "Rebuild the HTML report from result directories (shards merge; runs compare)");
  report->add_option("dirs", report_dirs, "Result directories (each with results.json)")
      ->required()
      ->check(CLI::ExistingDirectory);
  report->add_option("--out", report_out,
                     "Output HTML file (default DIR/report.html for one DIR); with --baseline a "
                     "folder or FILE.html");
  std::string report_baseline;
  double max_slowdown = 1.5;
  CLI::Option* baseline_option =
      report
          ->add_option(
              "--baseline", report_baseline,
              "Compare the one DIR against this earlier run: regressions page, JUnit, exit 1 "
              "when a verdict got worse or a time regressed")
          ->check(CLI::ExistingDirectory);
  report
      ->add_option("--max-slowdown", max_slowdown,
                   "With --baseline: a median this many times the baseline's, with the min-max "
                   "ranges apart, is a regression")
      ->check(CLI::Validator(
          [](std::string& text) {
            double value = 0;
            if (CLI::detail::lexical_cast(text, value) && value >= 1 && value <= 1e6)
              return std::string();
            return "must be a number in [1, 1e6], is '" + text + "'";
          },
          "in [1, 1e6]"))
      ->needs(baseline_option)
      ->capture_default_str();

  CertifyOptions certify_options;
  CertifyWorkerOptions worker_options;
  bool certify_worker_mode = false;
  std::string certify_shard;
  std::uint32_t certify_threads = 0;
  CLI::App* certify_command = app.add_subcommand(
      "certify",
      "Certify a port loaded from a shared library (C ABI: include/shadowcts/backend_abi.h): every "
      "case of a profile in worker processes, twice; writes a certificate (docs/certify.md)");
  certify_command->require_subcommand(0, 1);
  certify_command->add_option("--backend", certify_options.library,
                              "The port's shared library (e.g. libport.so)");
  certify_command
      ->add_option("--profile", certify_options.profile,
                   "Cases: conformance (the default fixtures), stiff (the numerical traps), fuzz "
                   "(the watertight, degenerate and differential generators) or all")
      ->check(CLI::IsMember({"conformance", "stiff", "fuzz", "all"}))
      ->capture_default_str();
  auto* fuzz_seed_option =
      certify_command
          ->add_option("--fuzz-seed", certify_options.fuzz.seed,
                       "Profiles fuzz and all: the seed the fuzz cases' inputs derive from")
          ->capture_default_str();
  auto* fuzz_count_option = certify_command
                                ->add_option("--fuzz-count", certify_options.fuzz.count,
                                             "Profiles fuzz and all: cases per fuzz generator")
                                ->check(CLI::Range(1u, 1000000u))
                                ->capture_default_str();
  certify_command->add_option(
      "--fixture", certify_options.fixtures,
      "Only these fixtures instead of a profile (repeatable; the certificate says \"custom\")");
  certify_command->add_option("--out", certify_options.out_dir, "Output folder (new or empty)");
  certify_command
      ->add_option("--timeout", certify_options.timeout_s,
                   "Seconds one worker process (one run of one case x variant) may take before it "
                   "is killed and the case is a Timeout")
      ->check(CLI::Validator(
          [](std::string& text) {
            double value = 0;
            if (CLI::detail::lexical_cast(text, value) && value >= 0.1 && value <= 86400)
              return std::string();
            return "must be a number of seconds in [0.1, 86400], is '" + text + "'";
          },
          "in [0.1, 86400]"))
      ->capture_default_str();
  double certify_shrink_timeout = 0;
  auto* shrink_timeout_option =
      certify_command
          ->add_option("--shrink-timeout", certify_shrink_timeout,
                       "Fuzz cases that crashed or hung are shrunk in a worker process per "
                       "candidate: seconds each may take (default: --timeout)")
          ->check(CLI::Range(0.1, 86400.0));
  certify_command
      ->add_option("--shrink-runs", certify_options.shrink_runs,
                   "Worker runs that shrinking one crash or hang may take (0: no shrinking)")
      ->check(CLI::Range(0u, 1000000u))
      ->capture_default_str();
  certify_command
      ->add_option("--shrink-seconds", certify_options.shrink_seconds,
                   "Seconds that shrinking one crash or hang may take (0: no shrinking)")
      ->check(CLI::Range(0.0, 86400.0 * 7))
      ->capture_default_str();
  certify_command->add_option(
      "--shard", certify_shard,
      "Certify only shard I of N (I/N, 0-based); join with `certify merge`");
  auto* certify_threads_option =
      certify_command->add_option("--threads", certify_threads, "Worker threads per process")
          ->check(CLI::Range(1, 4096));
  // The worker process the parent spawns (internal).
  certify_command->add_flag("--worker", certify_worker_mode)->group("");
  certify_command->add_option("--variant", worker_options.variant)->group("");
  certify_command->add_flag("--probe", worker_options.probe)->group("");
  certify_command->add_flag("--reproduce", worker_options.reproduce)->group("");
  certify_command->add_option("--worker-result", worker_options.result_file)->group("");
  certify_command->add_option("--case", worker_options.case_file)->group("");
  bool certify_no_images = false;
  certify_command->add_flag("--no-images", certify_no_images)->group("");
  std::string verify_dir;
  CLI::App* certify_verify = certify_command->add_subcommand(
      "verify",
      "Check a certificate: content hash, suite, case list, library, completeness, "
      "statuses; exit 0 accepted, 1 rejected");
  certify_verify->add_option("dir", verify_dir, "The certification folder")->required();
  std::string merge_out;
  std::vector<std::string> merge_dirs;
  CLI::App* certify_merge = certify_command->add_subcommand(
      "merge", "Join the shard certifications of one library into one certification folder");
  certify_merge->add_option("out", merge_out, "Output folder (new or empty)")->required();
  certify_merge->add_option("dirs", merge_dirs, "The shards' folders")
      ->required()
      ->check(CLI::ExistingDirectory);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? exit_pass : exit_bad_input;
  }

  try {
    if (*list) {
      print_listing(builtin_registry(), list_json, std::cout);
      return exit_pass;
    }
    if (*gbuffer) return write_gbuffer(gbuffer_case, gbuffer_fixture, gbuffer_out);
    if (*report && !report_baseline.empty())
      return compare_report_command(report_baseline, report_dirs, report_out, max_slowdown,
                                    std::cout);
    if (*report) return write_report_command(report_dirs, report_out, std::cout);
    if (*export_command) {
      const NamedCase named = case_named_by("export", export_case_file, export_fixture);
      export_case(named.c, named.samples, export_out, std::cout);
      return exit_pass;
    }
    if (*certify_verify) return verify_certificate(verify_dir, std::cout);
    if (*certify_merge) return merge_certificates(merge_out, merge_dirs, std::cout);
    if (*certify_command) {
      if (*certify_threads_option) certify_options.threads = certify_threads;
      if (certify_worker_mode) {
        if (worker_options.probe) {
          worker_options.library = certify_options.library;
          return certify_worker(worker_options, std::cout, std::cerr);
        }
        if (certify_options.fixtures.size() + (worker_options.case_file.empty() ? 0 : 1) != 1)
          throw UsageError("certify --worker: give exactly one --fixture or --case");
        if (worker_options.reproduce && !worker_options.case_file.empty())
          throw UsageError("certify --worker --reproduce: give the fuzz case by --fixture");
        worker_options.library = certify_options.library;
        if (!certify_options.fixtures.empty())
          worker_options.fixture = certify_options.fixtures.front();
        worker_options.images = !certify_no_images;
        worker_options.out_dir = certify_options.out_dir;
        worker_options.threads = certify_options.threads;
        return certify_worker(worker_options, std::cout, std::cerr);
      }
      if (!worker_options.case_file.empty() || certify_no_images)
        throw UsageError(
            "certify: --case and --no-images are for worker processes; certify cases by "
            "--profile or --fixture");
      if (*shrink_timeout_option) certify_options.shrink_timeout_s = certify_shrink_timeout;
      if (certify_options.out_dir.empty()) throw UsageError("certify: give --out DIR");
      if ((*fuzz_seed_option || *fuzz_count_option) &&
          (!certify_options.fixtures.empty() ||
           (certify_options.profile != "fuzz" && certify_options.profile != "all")))
        throw UsageError(
            "--fuzz-seed and --fuzz-count select the cases of the profiles fuzz and all; with "
            "--fixture, name fuzz cases as fuzz.<generator>.<seed>.<index>");
      if (!certify_shard.empty()) {
        RunOptions shard_options;
        parse_shard(certify_shard, shard_options);
        certify_options.shard_index = shard_options.shard_index;
        certify_options.shard_count = shard_options.shard_count;
      }
      certify_options.command_line.assign(argv, argv + argc);
      return certify(certify_options, std::cout, std::cerr);
    }
    if (*check)
      return check_frame(check_case, check_out, isatty(STDERR_FILENO) != 0, std::cout, std::cerr);

    for (const std::string& text : algorithm_texts)
      options.algorithms.push_back(parse_selection(text));
    if (*eps_option) options.eps_rel = eps_rel;
    if (*repeat_option) options.repeats = repeats;
    if (*threads_option) options.threads = threads;
    options.oracle = oracle == "exact"    ? OracleChoice::exact
                     : oracle == "embree" ? OracleChoice::embree
                                          : OracleChoice::automatic;
    if (!shard.empty()) parse_shard(shard, options);
    options.images = !no_images;
    options.progress = isatty(STDERR_FILENO) != 0;
    options.progress_lines = !options.progress;
    options.progress_line_seconds = progress_seconds;
    return run_suite(options, builtin_registry(), std::cout, std::cerr);
  } catch (const InputError& e) {
    std::cerr << "shadowcts: bad input: " << e.what() << "\n";
    return exit_bad_input;
  } catch (const UsageError& e) {
    std::cerr << "shadowcts: " << e.what() << "\n";
    return exit_bad_input;
  } catch (const OutputError& e) {
    std::cerr << "shadowcts: cannot write output: " << e.what() << "\n";
    return exit_internal_error;
  } catch (const std::exception& e) {
    std::cerr << "shadowcts: error: " << e.what() << "\n";
    return exit_internal_error;
  }
}
