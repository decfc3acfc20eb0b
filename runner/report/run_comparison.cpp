#include "run_comparison.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <stdexcept>

#include "html_text.h"
#include "json_display.h"
#include "summary_table.h"

namespace shadowcts {
namespace {

using nlohmann::ordered_json;

int severity(const std::string& verdict) {
  if (verdict == "Pass") return 0;
  if (verdict == "QualityWarning") return 1;
  if (verdict == "Fail") return 2;
  if (verdict == "Crash" || verdict == "Timeout") return 3;
  return -1;  // NotSupported (and anything unknown): not ranked
}

std::optional<TimeSpread> spread_of(const ordered_json& record) {
  const auto t = record.find("time_ms");
  if (t == record.end() || !t->is_object()) return std::nullopt;
  const auto median = t->find("median");
  if (median == t->end() || !median->is_number() || median->get<double>() <= 0) return std::nullopt;
  TimeSpread s;
  s.median = s.min = s.max = median->get<double>();
  // Version 1 has no min/max beside the median: take them from the runs.
  const auto runs = t->find("runs");
  if (runs != t->end() && runs->is_array())
    for (const ordered_json& run : *runs)
      if (run.is_number()) {
        s.min = std::min(s.min, run.get<double>());
        s.max = std::max(s.max, run.get<double>());
      }
  if (const auto lo = t->find("min"); lo != t->end() && lo->is_number()) s.min = lo->get<double>();
  if (const auto hi = t->find("max"); hi != t->end() && hi->is_number()) s.max = hi->get<double>();
  return s;
}

// Figures where a larger value is a worse answer; others (sample counts) are shown as changed.
bool more_is_worse(const std::string& key) {
  for (const char* part : {"leak", "false", "miss", "error", "mismatch", "unsound", "disagree",
                           "lighting_ratio", "over_budget", "invalid", "occlusion"})
    if (key.find(part) != std::string::npos) return true;
  return false;
}

std::vector<ErrorChange> error_changes(const ordered_json& before, const ordered_json& after) {
  std::map<std::string, const ordered_json*> old_fields, new_fields;
  std::vector<std::string> keys;
  auto collect = [&](const ordered_json& record, std::map<std::string, const ordered_json*>& to) {
    const auto error = record.find("error");
    if (error == record.end() || !error->is_object()) return;
    for (const auto& [key, value] : flatten_fields(*error)) {
      if (value->is_array() || value->is_object()) continue;  // the curve is in the report
      if (!old_fields.count(key) && !new_fields.count(key)) keys.push_back(key);
      to[key] = value;
    }
  };
  collect(before, old_fields);
  collect(after, new_fields);
  std::vector<ErrorChange> out;
  for (const std::string& key : keys) {
    const auto o = old_fields.find(key), n = new_fields.find(key);
    const ordered_json* a = o == old_fields.end() ? nullptr : o->second;
    const ordered_json* b = n == new_fields.end() ? nullptr : n->second;
    if (a && b && *a == *b) continue;
    ErrorChange c;
    c.key = key;
    c.before = a ? display_value(*a) : "absent";
    c.after = b ? display_value(*b) : "absent";
    c.worse = a && b && a->is_number() && b->is_number() && more_is_worse(key) &&
              b->get<double>() > a->get<double>();
    out.push_back(std::move(c));
  }
  return out;
}

RecordChange change_of(const ReportRecord& r, const std::string& case_name, double max_slowdown) {
  RecordChange c;
  c.name = r.name;
  c.label = r.label();
  c.case_name = case_name;
  const ordered_json* before = nullptr;
  const ordered_json* after = nullptr;
  for (const Version& v : r.versions) (v.dir == 0 ? before : after) = &v.json;
  if (before) {
    c.old_verdict = before->value("verdict", "");
    c.old_time = spread_of(*before);
  }
  if (after) {
    c.new_verdict = after->value("verdict", "");
    c.new_time = spread_of(*after);
  }
  if (!before || !after) return c;
  const int a = severity(c.old_verdict), b = severity(c.new_verdict);
  c.verdict_worse = (a >= 0 && b > a) || (a < 0 && b >= 2);
  c.verdict_better = a >= 0 && b >= 0 && b < a;
  if (c.old_time && c.new_time) {
    c.time_ratio = c.new_time->median / c.old_time->median;
    c.slower = *c.time_ratio > max_slowdown && c.new_time->min > c.old_time->max;
    c.faster = *c.time_ratio < 1 / max_slowdown && c.new_time->max < c.old_time->min;
  }
  c.errors = error_changes(*before, *after);
  return c;
}

std::string ratio_text(double ratio) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "×%.2f", ratio);
  return buffer;
}

std::string spread_text(const std::optional<TimeSpread>& t) {
  if (!t) return "—";
  return display_ms(t->median) + " ms (" + display_ms(t->min) + "–" + display_ms(t->max) + ")";
}

// What changed, in words, for the terminal and the page's plain cells.
std::string describe(const RecordChange& c) {
  std::string out;
  auto add = [&](const std::string& part) { out += (out.empty() ? "" : "; ") + part; };
  if (c.added()) return "new, " + c.new_verdict;
  if (c.removed()) return "removed, was " + c.old_verdict;
  if (c.old_verdict != c.new_verdict) add("verdict " + c.old_verdict + " -> " + c.new_verdict);
  if (c.slower || c.faster)
    add("time " + ratio_text(*c.time_ratio) + (c.slower ? " slower " : " faster ") +
        spread_text(c.old_time) + " -> " + spread_text(c.new_time));
  for (const ErrorChange& e : c.errors) add(e.key + " " + e.before + " -> " + e.after);
  return out;
}

std::string verdict_cell(const std::string& verdict) {
  if (verdict.empty()) return "<td>—</td>";
  return "<td class=\"verdict v-" + verdict_class(verdict) + "\">" + html_escape(verdict) + "</td>";
}

std::string table_html(const RunComparison& comparison, const std::string& id,
                       const std::string& title, const std::vector<std::string>& kinds) {
  std::string rows;
  std::size_t n = 0;
  for (const RecordChange& c : comparison.records) {
    if (std::find(kinds.begin(), kinds.end(), c.kind()) == kinds.end()) continue;
    ++n;
    std::string time = "<td class=\"num\">" + html_escape(spread_text(c.old_time)) +
                       "</td><td class=\"num\">" + html_escape(spread_text(c.new_time));
    if (c.time_ratio)
      time += " <span class=\"ratio" +
              std::string(c.slower   ? " slower"
                          : c.faster ? " faster"
                                     : "") +
              "\">" + ratio_text(*c.time_ratio) + "</span>";
    time += "</td>";
    std::string errors;
    for (const ErrorChange& e : c.errors)
      errors += "<span class=\"fig" + std::string(e.worse ? " worse" : "") + "\" data-field=\"" +
                html_escape(e.key) + "\"><span class=\"k\">" + html_escape(e.key) + "</span> " +
                html_escape(e.before) + " → " + html_escape(e.after) + "</span>";
    rows += "<tr data-record=\"" + html_escape(c.name) + "\" data-kind=\"" + c.kind() + "\"><td>" +
            html_escape(c.case_name) + "</td><td title=\"" + html_escape(c.name) + "\">" +
            html_escape(c.label) + "</td>" + verdict_cell(c.old_verdict) +
            verdict_cell(c.new_verdict) + time + "<td>" + errors + "</td></tr>\n";
  }
  std::string out = "<h2>" + html_escape(title) + " (" + std::to_string(n) + ")</h2>\n";
  if (n == 0) return out + "<p class=\"reason\">none</p>\n";
  // The runs' paths are in the heading; the columns say before and after.
  return out + "<table id=\"" + id +
         "\"><thead><tr><th>case</th><th>algorithm:variant [backend]</th><th>verdict "
         "before</th><th>after</th><th>median ms (min–max), before</th><th>after</th><th>error "
         "changes</th></tr></thead>\n<tbody>\n" +
         rows + "</tbody></table>\n";
}

const char* const comparison_style = R"(
body { font: 14px/1.4 system-ui, sans-serif; margin: 24px; color: #222; background: #fff; }
h1 { font-size: 22px; margin: 0 0 8px; }
h2 { font-size: 18px; margin: 24px 0 8px; border-top: 2px solid #ccc; padding-top: 10px; }
table { border-collapse: collapse; margin: 8px 0; }
th, td { border: 1px solid #ddd; padding: 3px 6px; vertical-align: top; text-align: left; font-size: 13px; }
td { overflow-wrap: anywhere; }
th { background: #f3f3f3; }
td.num { white-space: nowrap; text-align: right; }
.reason, .k { color: #666; }
.fig { display: inline-block; margin-right: 10px; white-space: nowrap; }
.fig.worse { color: #b00020; font-weight: 600; }
.ratio.slower { color: #b00020; font-weight: 600; }
.ratio.faster { color: #087f23; font-weight: 600; }
.verdict { font-weight: 600; }
.v-Pass { background: #d9f2dc; }
.v-Fail { background: #f8c9c4; }
.v-QualityWarning { background: #fbe8b5; }
.v-NotSupported { background: #eceff1; color: #555; }
.v-Crash, .v-Timeout { background: #e3b6e8; }
.counts span { margin-right: 14px; }
.counts .bad { color: #b00020; font-weight: 600; }
)";

}  // namespace

std::string RecordChange::kind() const {
  if (added()) return "new";
  if (removed()) return "removed";
  if (regression()) return "regression";
  if (verdict_better) return "fixed";
  return changed() ? "changed" : "unchanged";
}

std::size_t RunComparison::count(const std::string& kind) const {
  std::size_t n = 0;
  for (const RecordChange& c : records) n += c.kind() == kind;
  return n;
}

RunComparison compare_runs(const ReportData& data, double max_slowdown) {
  if (data.dirs.size() != 2)
    throw std::logic_error("compare_runs: needs the baseline and the new run");
  RunComparison out;
  out.old_label = data.dirs[0].label;
  out.new_label = data.dirs[1].label;
  out.max_slowdown = max_slowdown;
  std::vector<RecordChange> removed;
  for (const ReportCase& c : data.cases)
    for (const ReportRecord& r : c.records) {
      RecordChange change = change_of(r, c.name, max_slowdown);
      (change.removed() ? removed : out.records).push_back(std::move(change));
    }
  for (RecordChange& c : removed) out.records.push_back(std::move(c));
  return out;
}

std::string comparison_html(const RunComparison& comparison) {
  std::string out =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<title>shadowcts comparison</title>\n<style>" +
      std::string(comparison_style) +
      "</style>\n</head>\n<body>\n<h1>shadowcts: " + html_escape(comparison.new_label) +
      " against the baseline " + html_escape(comparison.old_label) + "</h1>\n";
  char slowdown[32];
  std::snprintf(slowdown, sizeof slowdown, "%g", comparison.max_slowdown);
  out +=
      "<p class=\"reason\">A regression is a worse verdict (Pass &lt; QualityWarning &lt; Fail "
      "&lt; Crash) or a median time more than " +
      std::string(slowdown) +
      " times the baseline's with the min–max ranges of the repeats apart.</p>\n"
      "<p class=\"counts\">";
  for (const char* kind : {"regression", "fixed", "changed", "new", "removed", "unchanged"}) {
    const std::size_t n = comparison.count(kind);
    const bool bad = std::string(kind) == "regression" && n > 0;
    out += "<span data-kind=\"" + std::string(kind) + "\" data-value=\"" + std::to_string(n) +
           "\"" + (bad ? " class=\"bad\"" : "") + ">" + std::to_string(n) + " " + kind + "</span>";
  }
  out += "</p>\n";
  out += table_html(comparison, "regressions", "Regressions", {"regression"});
  out += table_html(comparison, "fixes", "Fixed", {"fixed"});
  out += table_html(comparison, "changes", "Other changes", {"changed"});
  out += table_html(comparison, "new-records", "New records", {"new"});
  out += table_html(comparison, "removed-records", "Removed records", {"removed"});
  return out + "</body>\n</html>\n";
}

std::string comparison_junit(const RunComparison& comparison) {
  std::size_t tests = 0, failures = 0, skipped = 0;
  std::string cases;
  for (const RecordChange& c : comparison.records) {
    ++tests;
    cases += "    <testcase classname=\"" + html_escape(c.case_name) + "\" name=\"" +
             html_escape(c.name) + "\">";
    if (c.regression()) {
      ++failures;
      cases += "<failure type=\"Regression\" message=\"" + html_escape(describe(c)) + "\"/>";
    } else if (c.removed()) {
      ++skipped;
      cases += "<skipped message=\"" + html_escape("not in " + comparison.new_label) + "\"/>";
    } else if (c.changed() || c.added()) {
      cases += "<system-out>" + html_escape(describe(c)) + "</system-out>";
    }
    cases += "</testcase>\n";
  }
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"shadowcts compare\">\n"
         "  <testsuite name=\"" +
         html_escape("regressions against " + comparison.old_label) + "\" tests=\"" +
         std::to_string(tests) + "\" failures=\"" + std::to_string(failures) +
         "\" errors=\"0\" skipped=\"" + std::to_string(skipped) + "\">\n" + cases +
         "  </testsuite>\n</testsuites>\n";
}

void print_comparison(const RunComparison& comparison, std::ostream& out) {
  out << "compare " << comparison.new_label << " against the baseline " << comparison.old_label
      << "\n";
  for (const RecordChange& c : comparison.records) {
    const std::string kind = c.kind();
    if (kind == "unchanged") continue;
    char head[16];
    std::snprintf(head, sizeof head, "%-10s", kind.c_str());
    out << "  " << head << " " << c.name << ": " << describe(c) << "\n";
  }
  const std::size_t regressions = comparison.count("regression");
  out << regressions << (regressions == 1 ? " regression, " : " regressions, ")
      << comparison.count("fixed") << " fixed, " << comparison.count("changed") << " changed, "
      << comparison.count("new") << " new, " << comparison.count("removed") << " removed, "
      << comparison.count("unchanged") << " unchanged\n";
  out.flush();
}

}  // namespace shadowcts
