// Every registered algorithm x variant x backend on every default fixture is a CTest case, named
// like the runner's records (dots become underscores for GoogleTest), e.g.
// Conformance/hard_bruteforce_exact_reference_gate_house_20k.
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "shadowcts/fixtures.h"
#include "shadowcts/registry.h"
#include "shadowcts/runner.h"

namespace shadowcts {
namespace {

namespace fs = std::filesystem;

struct ConformanceCase {
  std::string fixture, algorithm, variant, backend;
};

// Readable parameter values in test logs.
void PrintTo(const ConformanceCase& c, std::ostream* os) {
  *os << c.algorithm << ":" << c.variant << " [" << c.backend << "] on " << c.fixture;
}

std::vector<ConformanceCase> all_cases() {
  std::vector<ConformanceCase> cases;
  for (const std::string& fixture : default_fixtures())
    for (const auto& a : builtin_registry().algorithms())
      for (const std::string& variant : a->info().variants)
        cases.push_back({fixture, a->info().id, variant, a->info().backend});
  return cases;
}

std::string case_name(const testing::TestParamInfo<ConformanceCase>& info) {
  std::string name = info.param.algorithm + "_" + info.param.variant + "_" + info.param.backend +
                     "_" + info.param.fixture;
  for (char& ch : name)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return name;
}

class Conformance : public testing::TestWithParam<ConformanceCase> {};

TEST_P(Conformance, PassesOrIsNotSupported) {
  const ConformanceCase& c = GetParam();
  const fs::path out = fs::temp_directory_path() / ("shadowcts_conformance_" + case_name({c, 0}));
  fs::remove_all(out);
  RunOptions options;
  options.fixtures = {c.fixture};
  options.algorithms = {{c.algorithm, c.variant}};
  options.backends = {c.backend};
  options.out_dir = out.string();
  options.repeats = 1;
  options.images = false;  // the verdicts are the test; images are the report's (Runner tests)
  // Every algorithm of a fixture is judged against the same truth: the first case of a fixture
  // computes it, the others read it (the soft oracle alone costs ~17 s per foliage.10k case).
  options.truth_cache_dir = SHADOWCTS_TRUTH_CACHE_DIR;
  std::ostringstream log, err;
  const int code = run_suite(options, builtin_registry(), log, err);
  std::ifstream in(out / "results.json");
  const auto results = nlohmann::json::parse(in);
  ASSERT_EQ(results["results"].size(), 1u) << log.str();
  const auto& record = results["results"][0];
  const std::string verdict = record["verdict"];
  if (verdict == "NotSupported") {
    EXPECT_EQ(code, exit_pass);
    // Shown as skipped, with the reason, so CI logs say what was not certified.
    GTEST_SKIP() << "NotSupported: " << record["reason"].get<std::string>();
  }
  // Approximate algorithms (shadow maps) report their robust mismatches as QualityWarning: their
  // error figures, not a failure.
  const Algorithm* algorithm = builtin_registry().find(c.algorithm, c.backend);
  ASSERT_NE(algorithm, nullptr);
  if (algorithm->info().capabilities.approximate && verdict == "QualityWarning") {
    EXPECT_EQ(code, exit_pass) << record["reason"];
    fs::remove_all(out);
    return;
  }
  EXPECT_EQ(verdict, "Pass") << record["reason"] << "\n" << log.str();
  EXPECT_EQ(code, exit_pass);
  fs::remove_all(out);
}

INSTANTIATE_TEST_SUITE_P(Conformance, Conformance, testing::ValuesIn(all_cases()), case_name);

}  // namespace
}  // namespace shadowcts
