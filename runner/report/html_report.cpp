#include "html_report.h"

#include <map>

#include "atomic_file.h"
#include "case_section.h"
#include "html_text.h"
#include "json_display.h"
#include "summary_table.h"
#include "svg_plot.h"
#include "verdict_matrix.h"

namespace shadowcts {
namespace {

using nlohmann::ordered_json;

const char* const page_style = R"(
body { font: 14px/1.4 system-ui, sans-serif; margin: 24px; color: #222; background: #fff; }
h1 { font-size: 22px; margin: 0 0 8px; }
h2 { font-size: 18px; margin: 28px 0 8px; border-top: 2px solid #ccc; padding-top: 12px; }
table { border-collapse: collapse; margin: 8px 0; }
th, td { border: 1px solid #ddd; padding: 3px 6px; vertical-align: top; text-align: left; }
th { background: #f3f3f3; font-weight: 600; }
td.num { white-space: nowrap; text-align: right; }
table.summary { width: 100%; table-layout: fixed; }
table.summary td { overflow-wrap: anywhere; }
table.summary th:nth-child(1) { width: 13%; }
table.summary th:nth-child(2) { width: 14%; }
tr.record td { font-size: 13px; }
.range, .reason { color: #666; font-size: 12px; }
.known-limit { color: #8a6d00; font-size: 12px; }
.range { display: block; }
.phase { display: block; font-size: 12px; margin-top: 2px; white-space: normal; }
.phase .k { color: #666; }
.phase .range { display: inline; }
.fig { display: inline-block; margin: 0 10px 2px 0; white-space: nowrap; }
.fig .k { color: #666; }
.verdict { font-weight: 600; }
.v-Pass { background: #d9f2dc; }
.v-Fail { background: #f8c9c4; }
.v-QualityWarning { background: #fbe8b5; }
.v-NotSupported { background: #eceff1; color: #555; }
.v-Crash, .v-Timeout { background: #e3b6e8; }
.changed { outline: 2px solid #e67e00; background-color: #fff1dc; }
.ratio.faster { color: #087f23; font-weight: 600; }
.ratio.slower { color: #b00020; font-weight: 600; }
tr.compared.first-version td { border-top: 2px solid #999; }
.only { color: #888; font-size: 12px; }
.plots { display: flex; flex-wrap: wrap; gap: 16px; }
svg.plot { background: #fff; border: 1px solid #e4e4e4; }
svg .grid { stroke: #e6e6e6; }
svg .tick, svg .legend { font-size: 11px; fill: #333; }
svg .axis-label { font-size: 12px; fill: #222; }
svg .plot-title { font-size: 13px; font-weight: 600; fill: #222; }
svg .empty { font-size: 13px; fill: #888; }
.images { margin-top: 8px; }
.image-row { display: flex; flex-wrap: wrap; gap: 10px; align-items: flex-start; margin: 6px 0; }
.row-label { width: 180px; font-weight: 600; }
figure { margin: 0; }
figure img { width: 256px; image-rendering: pixelated; border: 1px solid #ccc; display: block; }
figcaption { font-size: 11px; color: #555; max-width: 256px; word-break: break-all; }
.legend { margin: 4px 0; font-size: 12px; }
.legend-title { font-weight: 600; margin-right: 8px; }
.legend-entry { margin-right: 12px; white-space: nowrap; }
.swatch { display: inline-block; width: 12px; height: 12px; border: 1px solid #888; vertical-align: -2px; margin-right: 4px; }
.left-out ul { margin: 2px 0 6px; color: #555; font-size: 12px; }
.sources td, .sources th { font-size: 12px; }
div.facts { margin: 4px 0 8px; max-width: 1200px; }
div.facts .fig { white-space: normal; }
nav a { margin-right: 10px; }
.matrix-wrap { overflow-x: auto; }
#verdict-matrix th { font-size: 12px; white-space: nowrap; }
#verdict-matrix th.case { writing-mode: vertical-rl; transform: rotate(180deg); max-height: 160px; }
#verdict-matrix td.cell { font-size: 11px; text-align: center; white-space: nowrap; min-width: 64px; height: 30px; padding: 2px 4px; }
#verdict-matrix td.cell a { color: #111; text-decoration: none; display: block; }
#verdict-matrix td.cell .err { font-weight: 600; }
#verdict-matrix td.none { background: #fff; }
#verdict-matrix td.changed-verdict { outline: 3px solid #e67e00; outline-offset: -3px; }
.m-Pass { background: #7bc77f; }
.m-Fail { background: #e8675a; }
.m-QualityWarning { background: #f2c14e; }
.m-NotSupported { background: #cfd8dc; color: #555; }
.m-Crash, .m-Timeout { background: #b467c0; }
ul.not-supported { font-size: 12px; color: #444; margin: 2px 0 8px; }
ul.not-supported .count { color: #666; }
)";

std::string sources_html(const ReportData& data) {
  std::string out = "<table class=\"sources\"><tr><th>directory</th><th>run</th></tr>\n";
  for (std::size_t d = 0; d < data.dirs.size(); ++d) {
    out += "<tr><td>" + html_escape(data.dirs[d].label) + "</td><td>";
    // Machine (CPU, threads, the ISA Highway dispatches to), threads, timing: as recorded.
    for (const auto& [key, value] : flatten_fields(data.dirs[d].run))
      out += "<span class=\"fig\" data-dir=\"" + std::to_string(d) + "\" data-run-field=\"" +
             html_escape(key) + "\" data-value=\"" + html_escape(exact_text(*value)) +
             "\"><span class=\"k\">" + html_escape(key) + "</span> " +
             html_escape(display_value(*value)) + "</span>";
    out += "</td></tr>\n";
  }
  return out + "</table>\n";
}

std::string verdict_counts_html(const ReportData& data) {
  // Counted over every version, in order of first appearance.
  std::vector<std::string> order;
  std::map<std::string, std::size_t> counts;
  std::size_t total = 0;
  for (const ReportCase& c : data.cases)
    for (const ReportRecord& r : c.records)
      for (const Version& v : r.versions) {
        const std::string verdict = v.json.value("verdict", "");
        if (!counts.count(verdict)) order.push_back(verdict);
        ++counts[verdict];
        ++total;
      }
  std::string out = "<p class=\"verdict-counts\"><span data-field=\"results\" data-value=\"" +
                    std::to_string(total) + "\">" + std::to_string(total) + " results</span>";
  for (const std::string& verdict : order)
    out += " <span class=\"verdict v-" + verdict_class(verdict) + "\" data-verdict=\"" +
           html_escape(verdict) + "\" data-value=\"" + std::to_string(counts[verdict]) + "\">" +
           std::to_string(counts[verdict]) + " " + html_escape(verdict) + "</span>";
  return out + "</p>\n";
}

}  // namespace

std::string render_html_report(const ReportData& data) {
  std::string out =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
      "<title>shadowcts report</title>\n<style>" +
      std::string(page_style) + "</style>\n</head>\n<body>\n<h1>shadowcts report</h1>\n";
  out += sources_html(data);
  out += verdict_counts_html(data);
  if (data.has_comparisons())
    out +=
        "<p class=\"comparison-note\">Records present in several directories are shown one row "
        "per directory; a later row marks what differs from the first (outlined, the earlier "
        "value on hover) and its median time as a ratio (green: more than 10% faster, red: "
        "more than 10% slower).</p>\n";
  // At a glance first: which algorithm passes where, then error against time over every case.
  out += verdict_matrix_html(data);
  const std::vector<Plot> overview = overview_plots(data);
  if (!overview.empty()) {
    out += "<h2>Overview</h2>\n<div class=\"plots\">\n";
    for (const Plot& plot : overview) out += render_svg_plot(plot) + "\n";
    out += "</div>\n";
  }
  out += "<nav>";
  for (std::size_t i = 0; i < data.cases.size(); ++i)
    out +=
        "<a href=\"#case-" + std::to_string(i) + "\">" + html_escape(data.cases[i].name) + "</a>";
  out += "</nav>\n<h2>Summary</h2>\n";
  out += summary_table_html(data);
  for (std::size_t i = 0; i < data.cases.size(); ++i) out += case_section_html(data, i);
  return out + "</body>\n</html>\n";
}

void write_html_report(const std::vector<std::filesystem::path>& result_dirs,
                       const std::filesystem::path& out_file) {
  const std::filesystem::path page_dir = std::filesystem::absolute(out_file).parent_path();
  const ReportData data = load_report_data(result_dirs, page_dir);
  write_file_atomically(out_file, render_html_report(data));
}

}  // namespace shadowcts
