#pragma once
// `shadowcts run`: plans each case, runs the selected algorithms through the registry, diffs
// them against the oracle and writes results.json, junit.xml and images.
#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace shadowcts {

class Registry;

struct AlgorithmSelection {
  std::string id;
  std::string variant;  // empty: every variant
};

enum class OracleChoice { automatic, exact, embree };

struct RunOptions {
  std::vector<std::string> fixtures;    // fixture names; with case_files empty too: the default set
  std::vector<std::string> case_files;  // JSON case manifests
  std::string suite;                    // "stiff": every case of the stiff-case suite
  std::vector<AlgorithmSelection> algorithms;  // empty: every registered algorithm
  std::vector<std::string> backends;           // empty: every backend
  std::string out_dir = "shadowcts-out";
  std::optional<double> eps_rel;
  std::optional<std::uint32_t> repeats;  // timed repeats after one untimed warm-up run
  std::optional<std::uint32_t> threads;
  OracleChoice oracle = OracleChoice::automatic;
  // Keep oracle truths in this folder and take them from it for the same build and inputs
  // (runner/truth_cache.h); empty: no cache.
  std::string truth_cache_dir;
  // Run only the cases at positions shard_index, shard_index + shard_count, ... of the case list.
  std::uint32_t shard_index = 0;
  std::uint32_t shard_count = 1;
  // false: no PNG/EXR images (`run --no-images`): CI gating that reads only the verdicts saves
  // encoding them and loading OpenImageIO (~0.45 s per process); the report shows no images.
  bool images = true;
  bool progress = false;  // progress lines on stderr (the tool sets it when stderr is a terminal)
  // Otherwise a plain progress line on stderr once a minute while a long step runs (the tool sets
  // it when stderr is not a terminal: CI logs show a long case as it happens).
  bool progress_lines = false;
  double progress_line_seconds = 60.0;  // the interval of those lines
};

// Exit codes of the tool.
inline constexpr int exit_pass = 0;
inline constexpr int exit_conformance_failure = 1;
inline constexpr int exit_bad_input = 2;
inline constexpr int exit_internal_error = 3;  // e.g. an output that cannot be written

// Throws InputError / UsageError before anything is written when a case, G-buffer or option is
// invalid (an empty --out, an --out folder holding other files, a selection of nothing).
// The run goes into <out>.partial-<pid> and replaces <out> only when complete; an exception
// removes it, so <out> holds the previous run untouched. Throws OutputError naming the file when
// an output cannot be written (exit 3), never a Crash verdict.
int run_suite(const RunOptions& options, const Registry& registry, std::ostream& out,
              std::ostream& err);

}  // namespace shadowcts
