// Reading result directories back: merging shards, keeping versions for comparisons, refusing
// malformed input.
#include "report_data.h"

#include <fstream>

#include <gtest/gtest.h>

#include "report_test_support.h"
#include "shadowcts/errors.h"

namespace shadowcts {
namespace {

namespace fs = std::filesystem;
using nlohmann::ordered_json;
using namespace test;

TEST(ReportData, DisjointDirectoriesMergeIntoTheUnion) {
  const fs::path root = fresh_dir("merge_union");
  write_results(root / "shard0", {hand_case("a"), hand_case("c")},
                {hand_hard_record("a", "x", 1, 0), hand_hard_record("c", "x", 2, 0)});
  write_results(root / "shard1", {hand_case("b")},
                {hand_hard_record("b", "x", 3, 0), hand_hard_record("b", "y", 4, 0)});
  const ReportData data = load_report_data({root / "shard0", root / "shard1"}, root);
  ASSERT_EQ(data.cases.size(), 3u);
  EXPECT_EQ(data.cases[0].name, "a");
  EXPECT_EQ(data.cases[1].name, "c");
  EXPECT_EQ(data.cases[2].name, "b");
  EXPECT_EQ(data.cases[2].records.size(), 2u);
  for (const ReportCase& c : data.cases) {
    EXPECT_EQ(c.summaries.size(), 1u);
    for (const ReportRecord& r : c.records) EXPECT_EQ(r.versions.size(), 1u);
  }
  EXPECT_EQ(data.cases[2].summaries[0].dir, 1u);
  EXPECT_FALSE(data.has_comparisons());
  EXPECT_EQ(data.dirs[0].label, "shard0");
  EXPECT_EQ(data.dirs[0].run.value("threads", 0), 1);
  EXPECT_FALSE(data.dirs[0].run.contains("results"));
}

TEST(ReportData, SameRecordInTwoDirectoriesKeepsBothVersions) {
  const fs::path root = fresh_dir("merge_versions");
  write_results(root / "before", {hand_case("a")}, {hand_hard_record("a", "x", 10, 0)});
  write_results(root / "after", {hand_case("a")},
                {hand_hard_record("a", "x", 5, 3), hand_hard_record("a", "y", 1, 0)});
  const ReportData data = load_report_data({root / "before", root / "after"}, root / "page");
  ASSERT_EQ(data.cases.size(), 1u);
  const ReportCase& c = data.cases[0];
  EXPECT_EQ(c.summaries.size(), 2u);
  ASSERT_EQ(c.records.size(), 2u);
  ASSERT_EQ(c.records[0].versions.size(), 2u);
  EXPECT_EQ(c.records[0].versions[0].dir, 0u);
  EXPECT_EQ(c.records[0].versions[1].dir, 1u);
  EXPECT_EQ(c.records[0].versions[1].json["error"]["leaks"], 3);
  EXPECT_EQ(c.records[1].versions.size(), 1u);
  EXPECT_TRUE(data.has_comparisons());
  EXPECT_EQ(data.dirs[0].label, "../before");
  EXPECT_EQ(data.page_relative(1, "images/a/x.png"), "../after/images/a/x.png");
  EXPECT_EQ(c.records[0].label(), "x:exact [reference]");
}

TEST(ReportData, VersionOneDirectoriesCompareWithVersionTwo) {
  const fs::path root = fresh_dir("versions");
  write_results(root / "old", {hand_case("a")}, {hand_hard_record("a", "x", 10, 0)},
                "shadowcts.results/1");
  write_results(root / "new", {hand_case("a")}, {hand_hard_record("a", "x", 5, 0)});
  const ReportData data = load_report_data({root / "old", root / "new"}, root);
  ASSERT_EQ(data.cases.size(), 1u);
  ASSERT_EQ(data.cases[0].records.size(), 1u);
  EXPECT_EQ(data.cases[0].records[0].versions.size(), 2u);
}

TEST(ReportData, RefusesWhatIsNotAResultDirectory) {
  const fs::path root = fresh_dir("refuse");
  EXPECT_THROW(load_report_data({root / "missing"}, root), InputError);

  fs::create_directories(root / "not_json");
  std::ofstream(root / "not_json" / "results.json") << "{ nope";
  EXPECT_THROW(load_report_data({root / "not_json"}, root), InputError);

  fs::create_directories(root / "other_schema");
  std::ofstream(root / "other_schema" / "results.json")
      << R"({"schema": "shadowcts.results/3", "cases": [], "results": []})";
  EXPECT_THROW(load_report_data({root / "other_schema"}, root), InputError);

  write_results(root / "orphan", {hand_case("a")}, {hand_hard_record("b", "x", 1, 0)});
  EXPECT_THROW(load_report_data({root / "orphan"}, root), InputError);

  write_results(root / "twice", {hand_case("a")},
                {hand_hard_record("a", "x", 1, 0), hand_hard_record("a", "x", 2, 0)});
  EXPECT_THROW(load_report_data({root / "twice"}, root), InputError);

  // One folder given twice, also by another path: it would be compared with itself.
  write_results(root / "once", {hand_case("a")}, {hand_hard_record("a", "x", 1, 0)});
  EXPECT_THROW(load_report_data({root / "once", root / "once"}, root), UsageError);
  EXPECT_THROW(load_report_data({root / "once", root / "." / "once"}, root), UsageError);

  ordered_json nameless = hand_hard_record("a", "x", 1, 0);
  nameless.erase("name");
  write_results(root / "nameless", {hand_case("a")}, {nameless});
  EXPECT_THROW(load_report_data({root / "nameless"}, root), InputError);
}

// The message of the InputError that loading `dir` throws ("" when it loads).
std::string refusal(const fs::path& dir, const fs::path& root) {
  try {
    load_report_data({dir}, root);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ReportData, RefusesRecordsTheComparisonCouldNotJudge) {
  const fs::path root = fresh_dir("refuse_fields");
  // An unknown verdict would go unranked: a Pass that became one would be no regression.
  ordered_json typo = hand_hard_record("a", "x", 1, 0);
  typo["verdict"] = "Fial";
  write_results(root / "typo", {hand_case("a")}, {typo});
  EXPECT_NE(refusal(root / "typo", root).find("\"verdict\" is 'Fial', not one of Pass"),
            std::string::npos)
      << refusal(root / "typo", root);

  ordered_json kind = hand_hard_record("a", "x", 1, 0);
  kind["output"] = "shadow";
  write_results(root / "kind", {hand_case("a")}, {kind});
  EXPECT_NE(refusal(root / "kind", root).find("\"output\" is 'shadow'"), std::string::npos);

  for (const char* field : {"median", "min", "max"}) {
    ordered_json time = hand_hard_record("a", "x", 1, 0);
    time["time_ms"][field] = -1.0;
    write_results(root / field, {hand_case("a")}, {time});
    EXPECT_NE(refusal(root / field, root).find(std::string("time_ms.") + field + ": not a number"),
              std::string::npos)
        << field << ": " << refusal(root / field, root);
  }
  ordered_json phase = hand_hard_record("a", "x", 1, 0);
  phase["time_ms"]["phases"] = {{"build", {{"median", "fast"}}}};
  write_results(root / "phase", {hand_case("a")}, {phase});
  EXPECT_NE(refusal(root / "phase", root).find("time_ms.phases.build.median"), std::string::npos);

  // A number beyond double's range is a JSON error of the file, not an internal error.
  fs::create_directories(root / "huge");
  std::ofstream(root / "huge" / "results.json")
      << R"({"schema": "shadowcts.results/2", "threads": 1e999, "cases": [], "results": []})";
  EXPECT_NE(refusal(root / "huge", root).find("results.json: JSON:"), std::string::npos)
      << refusal(root / "huge", root);

  write_results(root / "fine", {hand_case("a")}, {hand_hard_record("a", "x", 1, 0)});
  EXPECT_EQ(refusal(root / "fine", root), "");
}

}  // namespace
}  // namespace shadowcts
