// The verdict matrix and the overview plots from hand-written runs: a cell per label and case
// (empty where a case lacks the label), the key figures, NotSupported folded with its reasons,
// and zero errors on the log-log overview.
#include <gtest/gtest.h>

#include "report_test_support.h"
#include "verdict_matrix.h"

namespace shadowcts {
namespace {

namespace fs = std::filesystem;
using namespace test;
using nlohmann::ordered_json;

std::size_t count(const std::string& text, const std::string& part) {
  std::size_t n = 0;
  for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

ReportData two_cases(const fs::path& dir) {
  ordered_json crashed = hand_hard_record("b", "crashy", 3, 0);
  crashed["verdict"] = "Crash";
  ordered_json unsupported_a = hand_hard_record("a", "never", 1, 0);
  ordered_json unsupported_b = hand_hard_record("b", "never", 1, 0);
  unsupported_a["verdict"] = unsupported_b["verdict"] = "NotSupported";
  unsupported_a["reason"] = "needs a sun disk";
  unsupported_b["reason"] = "no ranged lights";
  ordered_json partly = hand_hard_record("a", "partly", 1, 0);
  partly["verdict"] = "NotSupported";
  partly["reason"] = "too large";
  write_results(dir, {hand_case("a"), hand_case("b")},
                {hand_hard_record("a", "good", 2, 0), hand_hard_record("a", "leaky", 4, 3),
                 unsupported_a, partly, hand_hard_record("b", "good", 2, 0), crashed, unsupported_b,
                 hand_hard_record("b", "partly", 5, 0)});
  return load_report_data({dir}, dir);
}

TEST(VerdictMatrix, CellPerLabelAndCaseWithKeyFiguresAndFoldedNotSupported) {
  const fs::path dir = fresh_dir("matrix_hand");
  const std::string html = verdict_matrix_html(two_cases(dir));
  // Rows good, leaky, partly, crashy (never is folded); two cases each.
  EXPECT_EQ(count(html, "<tr data-label="), 4u);
  EXPECT_EQ(count(html, "<td class=\"cell"), 8u);
  EXPECT_EQ(count(html, "<td class=\"cell m-Pass\""), 3u);
  EXPECT_EQ(count(html, "<td class=\"cell none\""), 2u);  // leaky on b, crashy on a
  EXPECT_NE(html.find("<td class=\"cell m-Fail\" data-record=\"hard.leaky.exact.reference.a\""),
            std::string::npos);
  EXPECT_NE(html.find("4.00 ms<br><span class=\"err\">3 leaks</span>"), std::string::npos);
  EXPECT_NE(html.find("data-verdict=\"Crash\""), std::string::npos);
  // partly is NotSupported on one case only: a grey cell in its row, not folded.
  EXPECT_NE(html.find("<td class=\"cell m-NotSupported\" data-record=\"hard.partly.exact."
                      "reference.a\""),
            std::string::npos);
  EXPECT_EQ(html.find("<tr data-label=\"never"), std::string::npos);
  EXPECT_NE(html.find("<li data-algorithm=\"never\">"), std::string::npos);
  EXPECT_NE(html.find("needs a sun disk <span class=\"count\">(1 record)</span>; no ranged lights "
                      "<span class=\"count\">(1 record)</span>"),
            std::string::npos)
      << html;
  // Links point at the summary rows' ids: case 0, record 1 is leaky.
  EXPECT_NE(html.find("<a href=\"#" + record_anchor(0, 1) + "\">4.00 ms"), std::string::npos);
}

TEST(VerdictMatrix, RunsSideBySideShowTheLastVersionAndOutlineAChangedVerdict) {
  const fs::path root = fresh_dir("matrix_versions");
  write_results(root / "old", {hand_case("a")},
                {hand_hard_record("a", "same", 2, 0), hand_hard_record("a", "broke", 2, 0)});
  write_results(root / "new", {hand_case("a")},
                {hand_hard_record("a", "same", 3, 0), hand_hard_record("a", "broke", 2, 5)});
  const std::string html =
      verdict_matrix_html(load_report_data({root / "old", root / "new"}, root));
  EXPECT_EQ(count(html, "<td class=\"cell"), 2u);
  EXPECT_NE(html.find("<td class=\"cell m-Fail changed-verdict\" "
                      "data-record=\"hard.broke.exact.reference.a\""),
            std::string::npos);
  EXPECT_NE(html.find("(was Pass)"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"cell m-Pass\" data-record=\"hard.same.exact.reference.a\""),
            std::string::npos);
  EXPECT_NE(html.find("3.00 ms"), std::string::npos);  // the new run's time
}

TEST(OverviewPlot, ZeroErrorsSitADecadeBelowTheSmallestAndTheFrontSpansAllCases) {
  const fs::path dir = fresh_dir("overview_hand");
  const std::vector<Plot> plots = overview_plots(two_cases(dir));
  ASSERT_EQ(plots.size(), 1u);  // hard shadows only
  const Plot& plot = plots.front();
  EXPECT_TRUE(plot.x.log10);
  EXPECT_TRUE(plot.y.log10);
  // leaky's rate is 3/8 = 0.375: zero is drawn at 0.01.
  EXPECT_EQ(plot.y.label, "robust mismatch rate, log (0 drawn at 0.01)");
  std::size_t points = 0;
  for (const PlotSeries& s : plot.series)
    for (const PlotPoint& p : s.points) {
      ++points;
      EXPECT_EQ(p.y, p.record == "hard.leaky.exact.reference.a" ? 0.375 : 0.01) << p.record;
    }
  // Every judged record once: good twice, leaky, partly on b; not the NotSupported ones (hand
  // records keep their figures) nor the crash.
  EXPECT_EQ(points, 4u);
  // The fastest zero-error records (good on a and b, 2 ms) are the whole front.
  ASSERT_EQ(plot.front.size(), 2u);
  for (const PlotPoint& p : plot.front) {
    EXPECT_EQ(p.x, 2.0);
    EXPECT_EQ(p.y, 0.01);
  }
}

}  // namespace
}  // namespace shadowcts
