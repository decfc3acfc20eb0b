// `shadowcts report --baseline OLD NEW`: record changes between two runs, the regression page,
// JUnit and the exit code. Hand-written runs pin each kind of change; two real runs (the second
// with a planted regression) go through the tool itself.
#include <sys/wait.h>

#include <cstdlib>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "report_test_support.h"
#include "run_comparison.h"

namespace shadowcts {
namespace {

namespace fs = std::filesystem;
using namespace test;
using nlohmann::ordered_json;

const RecordChange& change(const RunComparison& c, const std::string& name) {
  for (const RecordChange& r : c.records)
    if (r.name == name) return r;
  throw std::runtime_error("no record " + name);
}

std::string name_of(const std::string& algorithm) {
  return "hard." + algorithm + ".exact.reference.hand";
}

TEST(RunComparison, EachKindOfChange) {
  const fs::path root = fresh_dir("compare_kinds");
  // hand_hard_record's repeats lie within ±25% of the median.
  write_results(
      root / "old", {hand_case("hand")},
      {hand_hard_record("hand", "worse", 10, 0), hand_hard_record("hand", "slow", 10, 0),
       hand_hard_record("hand", "noisy", 10, 0), hand_hard_record("hand", "fixed", 10, 2),
       hand_hard_record("hand", "faster", 10, 0), hand_hard_record("hand", "gone", 10, 0)});
  write_results(
      root / "new", {hand_case("hand")},
      {hand_hard_record("hand", "worse", 10, 3),
       // 3x: 22.5-37.5 ms against 7.5-12.5 ms.
       hand_hard_record("hand", "slow", 30, 0),
       // 1.6x, but 12-20 ms overlaps 7.5-12.5 ms: within the spread of the repeats.
       hand_hard_record("hand", "noisy", 16, 0), hand_hard_record("hand", "fixed", 10, 0),
       hand_hard_record("hand", "faster", 2, 0), hand_hard_record("hand", "added", 10, 1)});
  const ReportData data = load_report_data({root / "old", root / "new"}, root);
  const RunComparison c = compare_runs(data, 1.5);

  const RecordChange& worse = change(c, name_of("worse"));
  EXPECT_EQ(worse.kind(), "regression");
  EXPECT_TRUE(worse.verdict_worse);
  ASSERT_FALSE(worse.errors.empty());
  EXPECT_EQ(worse.errors.front().key, "leaks");
  EXPECT_EQ(worse.errors.front().before, "0");
  EXPECT_EQ(worse.errors.front().after, "3");
  EXPECT_TRUE(worse.errors.front().worse);

  const RecordChange& slow = change(c, name_of("slow"));
  EXPECT_EQ(slow.kind(), "regression");
  EXPECT_TRUE(slow.slower);
  EXPECT_DOUBLE_EQ(*slow.time_ratio, 3.0);
  EXPECT_DOUBLE_EQ(slow.new_time->min, 22.5);
  EXPECT_DOUBLE_EQ(slow.old_time->max, 12.5);

  const RecordChange& noisy = change(c, name_of("noisy"));
  EXPECT_EQ(noisy.kind(), "unchanged");
  EXPECT_FALSE(noisy.slower);
  EXPECT_DOUBLE_EQ(*noisy.time_ratio, 1.6);

  EXPECT_EQ(change(c, name_of("fixed")).kind(), "fixed");
  EXPECT_EQ(change(c, name_of("faster")).kind(), "changed");
  EXPECT_TRUE(change(c, name_of("faster")).faster);
  EXPECT_EQ(change(c, name_of("added")).kind(), "new");
  EXPECT_EQ(change(c, name_of("gone")).kind(), "removed");
  EXPECT_EQ(c.records.back().name, name_of("gone"));  // removed ones come last
  EXPECT_EQ(c.count("regression"), 2u);

  // A larger allowance keeps the 3x slowdown from being a regression; the verdict still is one.
  const RunComparison lenient = compare_runs(data, 4);
  EXPECT_EQ(change(lenient, name_of("slow")).kind(), "unchanged");
  EXPECT_EQ(lenient.count("regression"), 1u);

  const std::string page = comparison_html(c);
  EXPECT_NE(page.find("<table id=\"regressions\">"), std::string::npos);
  EXPECT_NE(page.find("data-record=\"" + name_of("worse") + "\" data-kind=\"regression\""),
            std::string::npos);
  EXPECT_NE(page.find("data-record=\"" + name_of("gone") + "\" data-kind=\"removed\""),
            std::string::npos);
  EXPECT_NE(page.find("data-kind=\"regression\" data-value=\"2\""), std::string::npos);
  const std::string junit = comparison_junit(c);
  EXPECT_NE(junit.find("failures=\"2\""), std::string::npos) << junit;
  EXPECT_NE(junit.find("name=\"" + name_of("slow") + "\"><failure type=\"Regression\""),
            std::string::npos)
      << junit;
}

TEST(RunComparison, NotSupportedIsUnrankedUnlessItNowFails) {
  const fs::path root = fresh_dir("compare_not_supported");
  ordered_json was_unsupported = hand_hard_record("hand", "runs_now", 10, 0);
  ordered_json stops = hand_hard_record("hand", "stops", 10, 0);
  was_unsupported["verdict"] = "NotSupported";
  write_results(root / "old", {hand_case("hand")}, {was_unsupported, stops});
  stops["verdict"] = "NotSupported";
  write_results(root / "new", {hand_case("hand")},
                {hand_hard_record("hand", "runs_now", 10, 1), stops});
  const RunComparison c = compare_runs(load_report_data({root / "old", root / "new"}, root), 1.5);
  EXPECT_EQ(change(c, name_of("runs_now")).kind(), "regression");
  EXPECT_EQ(change(c, name_of("stops")).kind(), "changed");
}

// Runs the tool; returns its exit status, stdout in `output`.
int run_tool(const std::string& arguments, const fs::path& work, std::string& output) {
  const fs::path out = work / "tool.stdout";
  const std::string command =
      std::string(SHADOWCTS_TOOL) + " " + arguments + " > '" + out.string() + "' 2>&1";
  const int status = std::system(command.c_str());
  output = read_text(out);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(RunComparison, ToolReportsAPlantedRegressionWithExitOne) {
  const fs::path root = fresh_dir("compare_tool");
  const fs::path old_run = root / "old", new_run = root / "new";
  run_small_suite(old_run);  // bruteforce and embree
  std::string output;
  // A second real run with a narrower selection: embree's records are gone from it.
  ASSERT_EQ(run_tool("run --fixture ground_blockers.2k --algorithm bruteforce:exact --repeat 2 "
                     "--threads 2 --out '" +
                         new_run.string() + "'",
                     root, output),
            0)
      << output;
  // Timing noise on a shared machine must not decide this part: no slowdown counts.
  const std::string compare = "report --baseline '" + old_run.string() + "' '" + new_run.string() +
                              "' --out '" + (root / "cmp").string() + "'";
  ASSERT_EQ(run_tool(compare + " --max-slowdown 1e6", root, output), 0) << output;
  EXPECT_NE(output.find("0 regressions"), std::string::npos) << output;
  EXPECT_NE(output.find("removed    hard.embree."), std::string::npos) << output;

  // Plant a regression: the new run's bruteforce record now leaks.
  auto results = ordered_json::parse(read_text(new_run / "results.json"));
  std::string planted;
  for (auto& r : results["results"])
    if (r["algorithm"] == "bruteforce" && r["verdict"] == "Pass") {
      r["verdict"] = "Fail";
      r["error"]["leaks"] = 4;
      planted = r["name"];
      break;
    }
  ASSERT_FALSE(planted.empty());
  std::ofstream(new_run / "results.json") << results.dump(2);

  ASSERT_EQ(run_tool(compare + " --max-slowdown 1e6", root, output), 1) << output;
  EXPECT_NE(output.find("regression " + planted + ": verdict Pass -> Fail; leaks 0 -> 4"),
            std::string::npos)
      << output;
  EXPECT_NE(output.find("1 regression,"), std::string::npos) << output;
  const std::string page = read_text(root / "cmp" / "compare.html");
  EXPECT_NE(page.find("data-record=\"" + planted + "\" data-kind=\"regression\""),
            std::string::npos);
  const std::string junit = read_text(root / "cmp" / "compare.junit.xml");
  EXPECT_NE(junit.find("name=\"" + planted + "\"><failure type=\"Regression\""), std::string::npos)
      << junit;

  // --out FILE.html puts the JUnit beside the page.
  ASSERT_EQ(run_tool("report --baseline '" + old_run.string() + "' '" + new_run.string() +
                         "' --max-slowdown 1e6 --out '" + (root / "page.html").string() + "'",
                     root, output),
            1)
      << output;
  EXPECT_TRUE(fs::exists(root / "page.html"));
  EXPECT_TRUE(fs::exists(root / "page.junit.xml"));

  // Usage errors: two new directories, no --out, a slowdown below 1.
  EXPECT_EQ(run_tool("report --baseline '" + old_run.string() + "' '" + new_run.string() + "' '" +
                         new_run.string() + "' --out '" + (root / "x").string() + "'",
                     root, output),
            2)
      << output;
  EXPECT_EQ(run_tool("report --baseline '" + old_run.string() + "' '" + new_run.string() + "'",
                     root, output),
            2)
      << output;
  EXPECT_EQ(run_tool(compare + " --max-slowdown 0.5", root, output), 2) << output;
  // --max-slowdown means nothing without a baseline.
  EXPECT_EQ(run_tool("report '" + new_run.string() + "' --max-slowdown 2", root, output), 2)
      << output;
}

}  // namespace
}  // namespace shadowcts
