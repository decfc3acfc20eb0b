// mutant_kill: runs the conformance suite on an executable whose reference algorithm carries one
// mutant (tests/mutants/catalogue) and succeeds only if the suite catches it — some record of
// the mutated algorithm gets Fail or Crash that the unmutated algorithm does not get. Cases run one
// at a time, in the order given, and the first one that kills the mutant ends the run, so the
// catalogue names its killing case.
// A mutant the listed cases cannot kill is documented with --survives "<the case it would need>":
// then surviving passes and being killed fails (the catalogue must be updated).
//   mutant_kill --mutant NAME --algorithm ID[:VARIANT] (--fixture NAME | --suite stiff)...
//               [--survives WHY]
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "expected_failures.h"
#include "shadowcts/registry.h"
#include "shadowcts/runner.h"

namespace {

using namespace shadowcts;
namespace fs = std::filesystem;

struct Arguments {
  std::string mutant;
  AlgorithmSelection algorithm;
  std::vector<std::string> fixtures;  // "suite:stiff" for the stiff suite
  std::string survives;               // why the cases cannot kill it; empty: they must
};

Arguments parse(int argc, char** argv) {
  Arguments a;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i], value = argv[i + 1];
    if (key == "--mutant") {
      a.mutant = value;
    } else if (key == "--algorithm") {
      const auto colon = value.find(':');
      a.algorithm = {value.substr(0, colon),
                     colon == std::string::npos ? "" : value.substr(colon + 1)};
    } else if (key == "--fixture") {
      a.fixtures.push_back(value);
    } else if (key == "--suite") {
      a.fixtures.push_back("suite:" + value);
    } else if (key == "--survives") {
      a.survives = value;
    } else {
      throw std::runtime_error("unknown argument " + key);
    }
  }
  if (argc % 2 != 1 || a.mutant.empty() || a.algorithm.id.empty() || a.fixtures.empty())
    throw std::runtime_error(
        "usage: mutant_kill --mutant NAME --algorithm ID[:VARIANT] (--fixture F | --suite S)...");
  return a;
}

// The records of the mutated algorithm that the suite failed, as "name: reason" lines. Records
// that fail without the mutant too (expected_failures.h) prove nothing and do not count.
std::vector<std::string> killing_records(const fs::path& results, const AlgorithmSelection& a) {
  std::ifstream in(results);
  const nlohmann::json json = nlohmann::json::parse(in);
  std::vector<std::string> kills;
  for (const nlohmann::json& r : json.at("results")) {
    if (r.at("algorithm") != a.id || expected_failure(r.at("name"))) continue;
    const std::string verdict = r.at("verdict");
    if (verdict == "Fail" || verdict == "Crash")
      kills.push_back(r.at("name").get<std::string>() + " " + verdict + ": " +
                      r.value("reason", std::string()));
  }
  return kills;
}

}  // namespace

int main(int argc, char** argv) try {
  const Arguments args = parse(argc, argv);
  const fs::path out_root = fs::current_path() / ("mutant-" + args.mutant);
  for (const std::string& fixture : args.fixtures) {
    RunOptions options;
    if (fixture.rfind("suite:", 0) == 0)
      options.suite = fixture.substr(6);
    else
      options.fixtures = {fixture};
    options.algorithms = {args.algorithm};
    options.repeats = 1;  // the verdict is what matters here, not the time
    options.out_dir = (out_root / fixture).string();
    std::ostringstream log, err;
    const int code = run_suite(options, builtin_registry(), log, err);
    const std::vector<std::string> kills =
        killing_records(fs::path(options.out_dir) / "results.json", args.algorithm);
    if (code == exit_conformance_failure && !kills.empty()) {
      std::cout << "KILLED " << args.mutant << " by " << fixture << "\n";
      for (const std::string& k : kills) std::cout << "  " << k << "\n";
      if (args.survives.empty()) return 0;
      std::cout << "the catalogue says it survives (" << args.survives
                << "): delete its survives: line\n";
      return 1;
    }
    if (code != exit_pass && code != exit_conformance_failure) {
      std::cout << "ERROR " << args.mutant << " on " << fixture << " (exit " << code << ")\n"
                << err.str();
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
