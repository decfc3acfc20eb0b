// The stiff-case suite for every registered algorithm x variant x backend: one CTest case per
// stiff case (the oracle runs once per case). No record may Fail or Crash except the known limits
// of runner/known_limits.h, which must still fail and say so in their records.
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "runner/known_limits.h"
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
    if (const RecordLimit* expected = stiff_record_limit(name)) {
      std::cout << "[ EXPECTED ] " << name << " " << verdict << ": "
                << record["reason"].get<std::string>() << " -- " << expected->why << "\n";
      // The user sees the same: the record names the limit that explains it.
      EXPECT_EQ(record.value("known_limit", ""), expected->why) << name;
      continue;
    }
    EXPECT_FALSE(record.contains("known_limit")) << name << " claims a limit the table lacks";
    ADD_FAILURE() << name << " " << verdict << ": " << record["reason"].get<std::string>()
                  << "\n  reproduce: " << record["reproduce"].get<std::string>();
  }
  // An expected failure that no longer fails has been fixed: the table must say so.
  for (const auto& record : results["results"]) {
    const std::string name = record["name"];
    if (stiff_record_limit(name) && !failed.count(name) && record["verdict"] != "NotSupported")
      ADD_FAILURE() << name << " is listed in runner/known_limits.cpp but now gets "
                    << record["verdict"].get<std::string>() << ": remove the entry";
  }
  if (!HasFailure()) fs::remove_all(out);
}

INSTANTIATE_TEST_SUITE_P(Stiff, StiffSuite, testing::ValuesIn(stiff_fixtures()),
                         test_support::param_test_name);

}  // namespace
}  // namespace shadowcts
