// The stiff-case suite for every registered algorithm x variant x backend: one CTest case per
// stiff case (the oracle runs once per case). No record may Fail or Crash except the expected
// failures of expected_failures.h, which must still fail.
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "expected_failures.h"
#include "shadowcts/fixtures.h"
#include "shadowcts/registry.h"
#include "shadowcts/runner.h"
#include "tests/test_name.h"

namespace shadowcts {
namespace {

namespace fs = std::filesystem;

class StiffSuite : public testing::TestWithParam<std::string> {};

TEST_P(StiffSuite, EveryAlgorithmPassesOrFailsAsExpected) {
  const std::string& fixture = GetParam();
  const fs::path out =
      fs::temp_directory_path() / ("shadowcts_stiff_" + test_support::test_name(fixture));
  fs::remove_all(out);
  RunOptions options;
  options.fixtures = {fixture};
  options.out_dir = out.string();
  options.repeats = 1;
  options.images = false;  // the verdicts are the test; images are the report's (Runner tests)
  std::ostringstream log, err;
  const int code = run_suite(options, builtin_registry(), log, err);
  ASSERT_TRUE(code == exit_pass || code == exit_conformance_failure) << err.str();
  std::ifstream in(out / "results.json");
  const auto results = nlohmann::json::parse(in);
  ASSERT_FALSE(results["results"].empty());

  std::set<std::string> failed;
  for (const auto& record : results["results"]) {
    const std::string name = record["name"], verdict = record["verdict"];
    const Algorithm* algorithm = builtin_registry().find(record["algorithm"], record["backend"]);
    ASSERT_NE(algorithm, nullptr) << name;
    // A QualityWarning (right on every robust sample, often wrong on ambiguous ones) is what
    // float methods show on these traps: reported, not a failure, as in `shadowcts run`.
    if (verdict == "QualityWarning" && !algorithm->info().capabilities.approximate)
      std::cout << "[ WARNING  ] " << name << ": " << record["reason"].get<std::string>() << "\n";
    if (verdict == "Pass" || verdict == "NotSupported" || verdict == "QualityWarning") continue;
    failed.insert(name);
    if (const ExpectedFailure* expected = expected_failure(name)) {
      std::cout << "[ EXPECTED ] " << name << " " << verdict << ": "
                << record["reason"].get<std::string>() << " -- " << expected->why << "\n";
      continue;
    }
    ADD_FAILURE() << name << " " << verdict << ": " << record["reason"].get<std::string>()
                  << "\n  reproduce: " << record["reproduce"].get<std::string>();
  }
  // An expected failure that no longer fails has been fixed: the table must say so.
  for (const auto& record : results["results"]) {
    const std::string name = record["name"];
    if (expected_failure(name) && !failed.count(name) && record["verdict"] != "NotSupported")
      ADD_FAILURE() << name << " is listed in expected_failures.h but now gets "
                    << record["verdict"].get<std::string>() << ": remove the entry";
  }
  if (!HasFailure()) fs::remove_all(out);
}

INSTANTIATE_TEST_SUITE_P(Stiff, StiffSuite, testing::ValuesIn(stiff_fixtures()),
                         test_support::param_test_name);

}  // namespace
}  // namespace shadowcts
