// Fails that a documented limit explains say so (runner/known_limits.h): the stiff table by record
// name, a fuzz generator's declared limits only where they cover every sample the record got
// wrong, and nothing else.
#include "known_limits.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "shadowcts/registry.h"
#include "shadowcts/runner.h"

namespace shadowcts {
namespace {

namespace fs = std::filesystem;

TEST(KnownLimits, TheStiffTableMatchesRecordNamesByGlob) {
  ASSERT_FALSE(stiff_record_limits().empty());
  const RecordLimit* zpass =
      stiff_record_limit("hard.stencil.zpass.reference.stiff.camera_in_shadow_volume");
  ASSERT_NE(zpass, nullptr);
  EXPECT_NE(std::string(zpass->why).find("eye"), std::string::npos);
  EXPECT_NE(stiff_record_limit("hard.embree.robust.embree.stiff.light_at_caster_vertex"), nullptr);
  // Another variant, backend or case is not covered.
  EXPECT_EQ(stiff_record_limit("hard.stencil.zfail.reference.stiff.camera_in_shadow_volume"),
            nullptr);
  EXPECT_EQ(stiff_record_limit("hard.embree.robust.embree.stiff.light_on_caster_edge"), nullptr);
  EXPECT_EQ(stiff_record_limit("hard.embree.robust.embree.fuzz.watertight.1.37"), nullptr);
  // A table entry explains the record whatever the samples.
  EXPECT_EQ(known_limit("hard.embree.robust.embree.stiff.light_at_caster_vertex", "embree",
                        "robust", {}, {}),
            stiff_record_limit("hard.embree.robust.embree.stiff.light_at_caster_vertex")->why);
}

TEST(KnownLimits, AGeneratorsLimitExplainsOnlyTheSamplesItCovers) {
  const std::string record = "hard.embree.robust.embree.fuzz.watertight.1.0";
  const std::vector<fuzzing::KnownLimit> whole_case = {{"embree", "crack", {}}};
  const std::vector<fuzzing::KnownLimit> some_samples = {{"embree", "vertex", {2, 5, 9}}};
  EXPECT_EQ(known_limit(record, "embree", "robust", whole_case, {0, 7}), "crack");
  EXPECT_EQ(known_limit(record, "embree", "robust", some_samples, {5}), "vertex");
  EXPECT_EQ(known_limit(record, "embree", "robust", some_samples, {2, 9}), "vertex");
  // A wrong sample outside the limit is a finding, not the limit.
  EXPECT_EQ(known_limit(record, "embree", "robust", some_samples, {2, 3}), "");
  // The limit is the peer's: another algorithm answering the same wrongly is not excused.
  EXPECT_EQ(known_limit("hard.ptsv.twopass.reference.fuzz.watertight.1.0", "ptsv", "twopass",
                        whole_case, {0}),
            "");
  // A failure with no wrong sample (a budget, a rerun that differed) is not the limit's.
  EXPECT_EQ(known_limit(record, "embree", "robust", whole_case, {}), "");
  EXPECT_EQ(known_limit(record, "embree", "robust", {}, {0}), "");
  // A limit that names a variant excuses that variant alone.
  const std::string zpass = "hard.stencil.zpass.reference.fuzz.differential.1.0";
  const std::string zfail = "hard.stencil.zfail.reference.fuzz.differential.1.0";
  const std::vector<fuzzing::KnownLimit> one_variant = {{"stencil", "eye", {}, "zpass"}};
  EXPECT_EQ(known_limit(zpass, "stencil", "zpass", one_variant, {0, 3}), "eye");
  EXPECT_EQ(known_limit(zfail, "stencil", "zfail", one_variant, {0, 3}), "");
}

// Embree leaks through the T-junction cracks of fuzz.watertight.1.37 (a limit the watertight
// generator declares for it): the record Fails and names the limit in results.json, JUnit, the
// report and the terminal, and the other algorithms that run on the case are right there.
TEST(KnownLimits, TheRunnerNamesTheLimitOfAFailedRecord) {
  const fs::path out = fs::temp_directory_path() / "shadowcts_known_limits_test";
  fs::remove_all(out);
  RunOptions options;
  options.fixtures = {"fuzz.watertight.1.37"};
  options.algorithms = {{"embree", ""}, {"ptsv", ""}};
  options.out_dir = out.string();
  options.repeats = 1;
  options.images = false;
  std::ostringstream log, err;
  ASSERT_EQ(run_suite(options, builtin_registry(), log, err), exit_conformance_failure)
      << err.str() << log.str();
  std::ifstream in(out / "results.json");
  const auto results = nlohmann::json::parse(in);
  std::size_t embree_records = 0, others = 0;
  for (const auto& record : results["results"]) {
    if (record["verdict"] == "NotSupported") continue;
    if (record["algorithm"] == "embree") {
      ++embree_records;
      EXPECT_EQ(record["verdict"], "Fail") << record.dump();
      EXPECT_EQ(record.value("known_limit", ""),
                "a float ray can slip through a T-junction's crack");
    } else {
      ++others;
      EXPECT_EQ(record["verdict"], "Pass") << record.dump();
      EXPECT_FALSE(record.contains("known_limit")) << record.dump();
    }
  }
  EXPECT_EQ(embree_records, 1u);
  EXPECT_GT(others, 0u);
  std::ifstream junit(out / "junit.xml");
  const std::string xml((std::istreambuf_iterator<char>(junit)), std::istreambuf_iterator<char>());
  EXPECT_NE(xml.find("(a known limit: a float ray can slip through a T-junction&#39;s crack)"),
            std::string::npos)
      << xml;
  std::ifstream html(out / "report.html");
  const std::string report((std::istreambuf_iterator<char>(html)),
                           std::istreambuf_iterator<char>());
  EXPECT_NE(report.find("<div class=\"known-limit\">a known limit: a float ray can slip"),
            std::string::npos);
  EXPECT_NE(log.str().find("    a known limit: a float ray can slip"), std::string::npos);
  EXPECT_NE(log.str().find("of the Fails, 1 is a known limit of its method"), std::string::npos)
      << log.str();
  fs::remove_all(out);
}

}  // namespace
}  // namespace shadowcts
