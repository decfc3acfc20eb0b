// The page: its numbers are the JSON's, every string from the JSON is inert, shards merge,
// before/after comparisons mark differences, and the output is deterministic and atomic.
#include "html_report.h"

#include <algorithm>
#include <cctype>
#include <regex>

#include <gtest/gtest.h>

#include "report_test_support.h"
#include "shadowcts/errors.h"

namespace shadowcts {
namespace {

namespace fs = std::filesystem;
using nlohmann::ordered_json;
using namespace test;

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

std::size_t count(const std::string& text, const std::string& part) {
  std::size_t n = 0;
  for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

TEST(HtmlReport, NumbersOnThePageAreTheJsons) {
  const fs::path dir = fresh_dir("numbers");
  run_small_suite(dir);
  write_html_report({dir}, dir / "report.html");
  const std::string page = read_text(dir / "report.html");
  const MarkedValues marked = marked_values(page);
  const ordered_json results = ordered_json::parse(read_text(dir / "results.json"));

  auto expect_marked = [&](const std::string& record, const std::string& field,
                           const ordered_json& value) {
    const auto it = marked.find({record, "0", field});
    ASSERT_NE(it, marked.end()) << record << " " << field << " is not marked on the page";
    // Compared as JSON values: the page carries the JSON's own spelling of every number.
    if (value.is_string())
      EXPECT_EQ(it->second, value.get<std::string>()) << record << " " << field;
    else
      EXPECT_EQ(ordered_json::parse(it->second), value) << record << " " << field;
  };
  std::size_t timed = 0, curve_points = 0, phased = 0;
  ASSERT_FALSE(results["results"].empty());
  for (const ordered_json& r : results["results"]) {
    const std::string name = r["name"];
    expect_marked(name, "verdict", r["verdict"]);
    if (r["verdict"] == "NotSupported") continue;
    ++timed;
    curve_points += r["error"]["mismatch_curve"].size();
    expect_marked(name, "time_ms.median", r["time_ms"]["median"]);
    if (r["time_ms"].contains("phases")) {
      ++phased;
      for (const auto& [phase, timing] : r["time_ms"]["phases"].items()) {
        const std::string field = "time_ms.phases." + phase + ".median";
        expect_marked(name, field, timing["median"]);
        const std::regex phase_range(
            "data-record=\"" + std::regex_replace(name, std::regex(R"([.\[\]])"), R"(\$&)") +
            "\" data-dir=\"0\" data-field=\"" +
            std::regex_replace(field, std::regex(R"([.])"), R"(\$&)") +
            R"re(" data-value="[^"]*" data-min="([^"]*)" data-max="([^"]*)")re");
        std::smatch m;
        ASSERT_TRUE(std::regex_search(page, m, phase_range)) << name << " " << phase;
        EXPECT_EQ(ordered_json::parse(std::string(m[1])), timing["min"]);
        EXPECT_EQ(ordered_json::parse(std::string(m[2])), timing["max"]);
      }
    }
    for (const auto& [key, value] : r["error"].items())
      if (!value.is_array()) expect_marked(name, "error." + key, value);
    for (const auto& [key, value] : r["counters"].items())
      expect_marked(name, "counters." + key, value);
    // min-max over the timed repeats.
    const auto& runs = r["time_ms"]["runs"];
    ASSERT_EQ(runs.size(), 2u);
    const double lo = std::min(runs[0].get<double>(), runs[1].get<double>());
    const double hi = std::max(runs[0].get<double>(), runs[1].get<double>());
    const std::regex range(
        "data-record=\"" + std::regex_replace(name, std::regex(R"([.\[\]])"), R"(\$&)") +
        R"re(" data-dir="0" data-field="time_ms.median" data-value="[^"]*" data-min="([^"]*)" data-max="([^"]*)")re");
    std::smatch m;
    ASSERT_TRUE(std::regex_search(page, m, range)) << name;
    EXPECT_EQ(std::stod(m[1]), lo);
    EXPECT_EQ(std::stod(m[2]), hi);
  }
  EXPECT_GE(timed, 2u);
  EXPECT_GE(phased, 1u);  // embree times its scene build and its rays
  // The machine as recorded, the ISA Highway dispatches to included.
  ASSERT_TRUE(results["machine"]["isa"].is_string());
  EXPECT_NE(page.find("data-run-field=\"machine.isa\" data-value=\"" +
                      results["machine"]["isa"].get<std::string>() + "\""),
            std::string::npos);
  // Every timed record is a point on its case's error-against-time plot, every curve point on the
  // curves; the overview above the cases has every timed record once more.
  const std::size_t sections = page.find("<section class=\"case\"");
  ASSERT_NE(sections, std::string::npos);
  EXPECT_EQ(count(page.substr(sections), "<g class=\"point\""), timed + curve_points);
  EXPECT_EQ(count(page.substr(0, sections), "<g class=\"point\""), timed);
  EXPECT_NE(page.find("data-verdict=\"Pass\" data-value=\"" + std::to_string(timed) + "\""),
            std::string::npos);
}

TEST(HtmlReport, StringsFromTheJsonStayInert) {
  const fs::path dir = fresh_dir("escaping");
  const std::string evil = "<script>alert('x')</script>\"&<b>";
  ordered_json c = hand_case(evil);
  c["left_out"] = {"<img src=x onerror=alert(1)>"};
  c["oracles"]["hard"]["mask_image"] = "images/\"><script>alert(2)</script>.png";
  ordered_json r = hand_hard_record(evil, "<i>algo</i>", 2, 1);
  r["reason"] = "</td></tr></table><script>alert(3)</script>";
  r["counters"] = {{"<u>count</u>", 7}};
  r["error"]["note"] = "<svg onload=alert(4)>";
  write_results(dir, {c}, {r});
  write_html_report({dir}, dir / "report.html");
  const std::string page = read_text(dir / "report.html");

  EXPECT_EQ(lower(page).find("<script"), std::string::npos);
  EXPECT_EQ(page.find("<b>"), std::string::npos);
  EXPECT_EQ(page.find("<i>"), std::string::npos);
  EXPECT_EQ(page.find("<u>"), std::string::npos);
  EXPECT_EQ(page.find("<img src=x"), std::string::npos);
  EXPECT_EQ(page.find("<svg onload"), std::string::npos);
  // The text survives, escaped, and reads back unchanged.
  EXPECT_NE(page.find("&lt;script&gt;alert(&#39;x&#39;)&lt;/script&gt;&quot;&amp;&lt;b&gt;"),
            std::string::npos);
  const MarkedValues marked = marked_values(page);
  EXPECT_EQ(marked.at({r["name"], "0", "counters.<u>count</u>"}), "7");
  EXPECT_EQ(marked.at({r["name"], "0", "error.note"}), "<svg onload=alert(4)>");
  // Image paths become URL paths: no quote can end the attribute.
  for (const std::string& src : image_sources(page))
    EXPECT_EQ(src.find_first_of("\"<> "), std::string::npos) << src;
}

TEST(HtmlReport, ShardsMergeIntoOnePageWithEveryCase) {
  const fs::path root = fresh_dir("shards");
  write_results(root / "shard0", {hand_case("a")}, {hand_hard_record("a", "x", 1, 0)});
  write_results(root / "shard1", {hand_case("b")}, {hand_hard_record("b", "x", 2, 0)});
  write_html_report({root / "shard0", root / "shard1"}, root / "merged.html");
  const std::string page = read_text(root / "merged.html");
  EXPECT_EQ(count(page, "<section class=\"case\""), 2u);
  EXPECT_NE(page.find("data-case=\"a\""), std::string::npos);
  EXPECT_NE(page.find("data-case=\"b\""), std::string::npos);
  // Nothing is marked as changed (the word only appears in the style sheet).
  EXPECT_EQ(page.find(" changed\""), std::string::npos);
  EXPECT_EQ(page.find("class=\"changed\""), std::string::npos);
  EXPECT_EQ(page.find("comparison-note"), std::string::npos);
  const MarkedValues marked = marked_values(page);
  EXPECT_EQ(marked.at({"hard.x.exact.reference.a", "0", "time_ms.median"}), "1.0");
  EXPECT_EQ(marked.at({"hard.x.exact.reference.b", "1", "time_ms.median"}), "2.0");
  // Each shard's images are referenced relative to the page.
  EXPECT_NE(page.find("src=\"shard1/images/b/oracle.mask.png\""), std::string::npos);
}

TEST(HtmlReport, SameRecordInTwoRunsIsComparedSideBySide) {
  const fs::path root = fresh_dir("compare");
  write_results(root / "before", {hand_case("a")}, {hand_hard_record("a", "x", 10, 0)});
  write_results(root / "after", {hand_case("a")}, {hand_hard_record("a", "x", 5, 3)});
  write_html_report({root / "before", root / "after"}, root / "compare.html");
  const std::string page = read_text(root / "compare.html");
  EXPECT_NE(page.find("comparison-note"), std::string::npos);
  const std::string name = "hard.x.exact.reference.a";
  const MarkedValues marked = marked_values(page);
  EXPECT_EQ(marked.at({name, "0", "error.leaks"}), "0");
  EXPECT_EQ(marked.at({name, "1", "error.leaks"}), "3");
  // The later version's changed figures are marked, with the earlier value on hover.
  EXPECT_NE(
      page.find(
          "<span class=\"fig changed\" data-record=\"" + name +
          "\" data-dir=\"1\" data-field=\"error.leaks\" data-value=\"3\" title=\"before: 0\""),
      std::string::npos);
  EXPECT_NE(page.find("verdict v-Fail changed\" data-record=\"" + name + "\" data-dir=\"1\""),
            std::string::npos);
  // Unchanged figures are not marked; the time shows as a ratio.
  EXPECT_NE(page.find("<span class=\"fig\" data-record=\"" + name +
                      "\" data-dir=\"1\" data-field=\"error.false_shadows\""),
            std::string::npos);
  EXPECT_NE(page.find("<span class=\"ratio faster\""), std::string::npos);
  EXPECT_NE(page.find("×0.50"), std::string::npos);
  // Both versions' points are on the plot, in different marker shapes; the overview shows the
  // last version's (a circle).
  EXPECT_EQ(count(page, "<g class=\"point\" data-record=\"" + name + "\"><circle"), 1u + 15u + 1u);
  EXPECT_EQ(count(page, "<g class=\"point\" data-record=\"" + name + "\"><rect"), 1u + 15u);
}

TEST(HtmlReport, PhasesShowUnderTheTotalAndCompareWithVersionOne) {
  const fs::path root = fresh_dir("phases");
  ordered_json phased = hand_hard_record("a", "x", 8, 0);
  phased["time_ms"]["phases"] = {
      {"build", {{"median", 2.0}, {"min", 1.5}, {"max", 2.5}, {"runs", {2.5, 2.0, 1.5}}}},
      {"query", {{"median", 5.0}, {"min", 4.0}, {"max", 6.0}, {"runs", {6.0, 5.0, 4.0}}}}};
  ordered_json faster = phased;
  faster["time_ms"]["phases"]["build"]["median"] = 1.0;
  // A version-1 directory (no phases) beside two version-2 ones.
  write_results(root / "v1", {hand_case("a")}, {hand_hard_record("a", "x", 10, 0)},
                "shadowcts.results/1");
  write_results(root / "v2", {hand_case("a")}, {phased});
  write_results(root / "v2b", {hand_case("a")}, {faster});
  write_html_report({root / "v2", root / "v1", root / "v2b"}, root / "compare.html");
  const std::string page = read_text(root / "compare.html");
  const std::string name = "hard.x.exact.reference.a";
  const MarkedValues marked = marked_values(page);
  EXPECT_EQ(marked.at({name, "0", "time_ms.phases.build.median"}), "2.0");
  EXPECT_EQ(marked.at({name, "0", "time_ms.phases.query.median"}), "5.0");
  EXPECT_FALSE(marked.count({name, "1", "time_ms.phases.build.median"}));
  EXPECT_EQ(marked.at({name, "2", "time_ms.phases.build.median"}), "1.0");
  // Against the first version: build twice as fast, query unchanged.
  EXPECT_NE(page.find("<span class=\"ratio faster\" title=\"build median against v2\">×0.50"),
            std::string::npos);
  EXPECT_NE(page.find("<span class=\"ratio\" title=\"query median against v2\">×1.00"),
            std::string::npos);
  // Build and query sit under the total, labelled.
  EXPECT_NE(page.find("<span class=\"k\">build</span> 2.00"), std::string::npos);
  EXPECT_NE(page.find("<span class=\"k\">query</span> 5.00"), std::string::npos);
}

TEST(HtmlReport, SameInputSameBytesAndNothingHalfWritten) {
  const fs::path dir = fresh_dir("deterministic");
  write_results(dir, {hand_case("a")},
                {hand_hard_record("a", "x", 1, 0), hand_hard_record("a", "y", 0.5, 2)});
  write_html_report({dir}, dir / "one.html");
  write_html_report({dir}, dir / "two.html");
  EXPECT_EQ(read_text(dir / "one.html"), read_text(dir / "two.html"));

  // A broken input leaves the earlier page alone and no partial file behind.
  const std::string before = read_text(dir / "one.html");
  fs::create_directories(dir / "broken");
  EXPECT_THROW(write_html_report({dir / "broken"}, dir / "one.html"), InputError);
  EXPECT_EQ(read_text(dir / "one.html"), before);
  for (const auto& entry : fs::directory_iterator(dir))
    EXPECT_EQ(entry.path().string().find(".partial"), std::string::npos) << entry.path();
}

TEST(HtmlReport, ThePageIsSelfContained) {
  const fs::path dir = fresh_dir("self_contained");
  write_results(dir, {hand_case("a")}, {hand_hard_record("a", "x", 1, 0)});
  write_html_report({dir}, dir / "report.html");
  const std::string page = lower(read_text(dir / "report.html"));
  EXPECT_EQ(page.find("<script"), std::string::npos);
  EXPECT_EQ(page.find("<link"), std::string::npos);
  EXPECT_EQ(count(page, "http://"), count(page, "http://www.w3.org/2000/svg"));
  EXPECT_EQ(page.find("https://"), std::string::npos);
  EXPECT_EQ(page.find("@import"), std::string::npos);
}

}  // namespace
}  // namespace shadowcts
