// mutant_kill: runs the conformance suite on an executable whose algorithm (a reference or a port)
// carries one mutant (tests/mutants/catalogue) and succeeds only if the suite catches it: some
// record of the mutated algorithm gets Fail (a robust mismatch, a missing light, a soft sample over
// budget) while the unmutated algorithm passes the same record. The unmutated verdicts come from
// the suite's own `shadowcts` program, run on the same case in a child process: this executable
// cannot hold the original of the mutated source next to the mutated one, and judging against a
// list of known failures would credit a mutant with a case that nothing ever runs unmutated.
// Cases run one at a time, in the order given, and the first one that kills the mutant ends the
// run, so the catalogue names its killing case.
// A mutant the listed cases cannot kill is documented with --survives "<the case it would need>":
// then surviving passes and being killed fails (the catalogue must be updated).
// A mutant that plants its bug into a port of a kind this suite does not have (the edge order of a
// port whose planes are float32) names that port's other bug as a mutant of its own, the control:
// a record counts as a kill only where the control passes it too, so the kill is the mutant's own
// bug and not the control's.
//   mutant_kill --mutant NAME --unmutated PATH_TO_SHADOWCTS --algorithm ID[:VARIANT]
//               [--backend NAME]... (--fixture NAME | --suite stiff)... [--survives WHY]
//               [--control NAME --control-program PATH_TO_ITS_MUTANT]
// Every mutant executable also answers the subset of `shadowcts run` used below, so that it can
// serve as another mutant's control:
//   mutant_kill run --algorithm ID[:VARIANT] [--backend NAME]... --repeat 1 --no-images --out DIR
//               (--fixture NAME | --suite stiff)
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "shadowcts/registry.h"
#include "shadowcts/runner.h"

namespace {

using namespace shadowcts;
namespace fs = std::filesystem;

struct Arguments {
  std::string mutant;
  std::string unmutated;  // the `shadowcts` program, built from the unmutated sources
  AlgorithmSelection algorithm;
  std::string algorithm_text;            // ID[:VARIANT] as given
  std::vector<std::string> backends;     // only these backends; empty: all
  std::vector<std::string> fixtures;     // "suite:stiff" for the stiff suite
  std::string survives;                  // why the cases cannot kill it; empty: they must
  std::string control, control_program;  // the control mutant and its executable; or empty
};

// "ID[:VARIANT]" as a selection.
AlgorithmSelection selection_of(const std::string& text) {
  const auto colon = text.find(':');
  return {text.substr(0, colon), colon == std::string::npos ? "" : text.substr(colon + 1)};
}

Arguments parse(int argc, char** argv) {
  Arguments a;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i], value = argv[i + 1];
    if (key == "--mutant") {
      a.mutant = value;
    } else if (key == "--unmutated") {
      a.unmutated = value;
    } else if (key == "--algorithm") {
      a.algorithm = selection_of(value);
      a.algorithm_text = value;
    } else if (key == "--backend") {
      a.backends.push_back(value);
    } else if (key == "--fixture") {
      a.fixtures.push_back(value);
    } else if (key == "--suite") {
      a.fixtures.push_back("suite:" + value);
    } else if (key == "--survives") {
      a.survives = value;
    } else if (key == "--control") {
      a.control = value;
    } else if (key == "--control-program") {
      a.control_program = value;
    } else {
      throw std::runtime_error("unknown argument " + key);
    }
  }
  if (argc % 2 != 1 || a.mutant.empty() || a.unmutated.empty() || a.algorithm.id.empty() ||
      a.fixtures.empty() || a.control.empty() != a.control_program.empty())
    throw std::runtime_error(
        "usage: mutant_kill --mutant NAME --unmutated SHADOWCTS --algorithm ID[:VARIANT] "
        "[--backend B]... (--fixture F | --suite S)... [--survives WHY] "
        "[--control NAME --control-program PATH]");
  return a;
}

// Record name -> {verdict, reason}.
using RecordVerdicts = std::map<std::string, std::pair<std::string, std::string>>;

// Every record of `algorithm` in a results.json.
RecordVerdicts verdicts(const fs::path& results, const std::string& algorithm) {
  std::ifstream in(results);
  if (!in) throw std::runtime_error("cannot read " + results.string());
  const nlohmann::json json = nlohmann::json::parse(in);
  RecordVerdicts out;
  for (const nlohmann::json& r : json.at("results"))
    if (r.at("algorithm") == algorithm)
      out[r.at("name").get<std::string>()] = {r.at("verdict").get<std::string>(),
                                              r.value("reason", std::string())};
  return out;
}

// Runs `program run` (the unmutated `shadowcts`, or a control mutant) on the same case and
// selection; returns its exit status.
int run_program(const std::string& program, const Arguments& args, const std::string& fixture,
                const fs::path& out_dir) {
  std::vector<std::string> command = {program,         "run", "--algorithm", args.algorithm_text,
                                      "--repeat",      "1",   "--no-images", "--out",
                                      out_dir.string()};
  for (const std::string& backend : args.backends)
    command.insert(command.end(), {"--backend", backend});
  if (fixture.rfind("suite:", 0) == 0) {
    command.insert(command.end(), {"--suite", fixture.substr(6)});
  } else {
    command.insert(command.end(), {"--fixture", fixture});
  }
  std::vector<char*> argv;
  for (std::string& s : command) argv.push_back(s.data());
  argv.push_back(nullptr);
  std::cout << std::flush;
  const pid_t child = fork();
  if (child < 0) throw std::runtime_error("fork failed");
  if (child == 0) {
    // The child's own summary would interleave with this log; its results.json is what counts.
    if (!std::freopen("/dev/null", "w", stdout)) _exit(127);
    execv(argv[0], argv.data());
    _exit(127);
  }
  int status = 0;
  if (waitpid(child, &status, 0) != child) throw std::runtime_error("waitpid failed");
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// `program run` on the case, then its records; nullopt, after saying why, when it did not finish.
// what: "unmutated" or "control NAME", for the message.
std::optional<RecordVerdicts> verdicts_of_run(const std::string& what, const std::string& program,
                                              const Arguments& args, const std::string& fixture,
                                              const fs::path& out_dir) {
  const int code = run_program(program, args, fixture, out_dir);
  if (code != exit_pass && code != exit_conformance_failure) {
    std::cout << "ERROR " << what << " " << program << " on " << fixture << " (exit " << code
              << ")\n";
    return std::nullopt;
  }
  return verdicts(out_dir / "results.json", args.algorithm.id);
}

// `run` mode: this mutant's verdicts on one case, written to DIR/results.json.
int run_mode(int argc, char** argv) {
  RunOptions options;
  for (int i = 2; i < argc; ++i) {
    const std::string key = argv[i];
    if (key == "--no-images") {
      options.images = false;
      continue;
    }
    if (i + 1 == argc) throw std::runtime_error("run: " + key + " needs a value");
    const std::string value = argv[++i];
    if (key == "--algorithm") {
      options.algorithms = {selection_of(value)};
    } else if (key == "--repeat") {
      options.repeats = std::uint32_t(std::stoul(value));
    } else if (key == "--out") {
      options.out_dir = value;
    } else if (key == "--backend") {
      options.backends.push_back(value);
    } else if (key == "--fixture") {
      options.fixtures = {value};
    } else if (key == "--suite") {
      options.suite = value;
    } else {
      throw std::runtime_error("run: unknown argument " + key);
    }
  }
  std::ostringstream log;
  return run_suite(options, builtin_registry(), log, std::cerr);
}

}  // namespace

int main(int argc, char** argv) try {
  if (argc > 1 && std::string(argv[1]) == "run") return run_mode(argc, argv);
  const Arguments args = parse(argc, argv);
  const fs::path out_root = fs::current_path() / ("mutant-" + args.mutant);
  for (const std::string& fixture : args.fixtures) {
    RunOptions options;
    if (fixture.rfind("suite:", 0) == 0)
      options.suite = fixture.substr(6);
    else
      options.fixtures = {fixture};
    options.algorithms = {args.algorithm};
    options.backends = args.backends;
    options.repeats = 1;     // the verdict is what matters here, not the time
    options.images = false;  // nor the pictures
    options.out_dir = (out_root / fixture / "mutated").string();
    std::ostringstream log, err;
    const int code = run_suite(options, builtin_registry(), log, err);
    if (code != exit_pass && code != exit_conformance_failure) {
      std::cout << "ERROR " << args.mutant << " on " << fixture << " (exit " << code << ")\n"
                << err.str();
      return 1;
    }
    std::vector<std::string> kills;
    if (code == exit_conformance_failure) {
      // Only now is the unmutated run needed: a case without a failed record cannot kill.
      const std::optional<RecordVerdicts> unmutated = verdicts_of_run(
          "unmutated", args.unmutated, args, fixture, out_root / fixture / "unmutated");
      if (!unmutated) return 1;
      std::optional<RecordVerdicts> control;
      if (!args.control.empty()) {
        control = verdicts_of_run("control " + args.control, args.control_program, args, fixture,
                                  out_root / fixture / ("control-" + args.control));
        if (!control) return 1;
      }
      const auto passes = [](const std::string& verdict) {
        return verdict == "Pass" || verdict == "QualityWarning";
      };
      for (const auto& [name, verdict] :
           verdicts(fs::path(options.out_dir) / "results.json", args.algorithm.id)) {
        if (verdict.first != "Fail") continue;
        const auto same = unmutated->find(name);
        if (same == unmutated->end()) {
          std::cout << "ERROR the unmutated run has no record " << name << "\n";
          return 1;
        }
        if (!passes(same->second.first)) {
          std::cout << "  not a kill, fails unmutated too: " << name << " (" << same->second.first
                    << ")\n";
          continue;
        }
        std::string control_verdict;
        if (control) {
          const auto other = control->find(name);
          if (other == control->end()) {
            std::cout << "ERROR the control run has no record " << name << "\n";
            return 1;
          }
          if (!passes(other->second.first)) {
            std::cout << "  not a kill, the control " << args.control << " fails it too: " << name
                      << " (" << other->second.first << ")\n";
            continue;
          }
          control_verdict = ", control " + args.control + ": " + other->second.first;
        }
        kills.push_back(name + " Fail (unmutated: " + same->second.first + control_verdict +
                        "): " + verdict.second);
      }
    }
    if (!kills.empty()) {
      std::cout << "KILLED " << args.mutant << " by " << fixture << "\n";
      for (const std::string& k : kills) std::cout << "  " << k << "\n";
      if (args.survives.empty()) return 0;
      std::cout << "the catalogue says it survives (" << args.survives
                << "): delete its survives: line\n";
      return 1;
    }
    std::cout << "survived " << fixture << "\n";
  }
  if (!args.survives.empty()) {
    std::cout << "SURVIVES " << args.mutant << " (documented): " << args.survives << "\n";
    return 0;
  }
  std::cout << "SURVIVED " << args.mutant << ": no case in the list fails it\n";
  return 1;
} catch (const std::exception& e) {
  std::cerr << "mutant_kill: " << e.what() << "\n";
  return 1;
}
