#include "verdict_matrix.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "case_plots.h"
#include "html_text.h"
#include "json_display.h"
#include "pareto_front.h"
#include "summary_table.h"

namespace shadowcts {
namespace {

using nlohmann::ordered_json;

struct MatrixRow {
  std::string label, algorithm;
  // Per case: (record index in the case) or none.
  std::vector<const ReportRecord*> cells;
  std::vector<std::size_t> record_index;
};

double number_at(const ordered_json& object, const char* key) {
  const auto it = object.find(key);
  return it != object.end() && it->is_number() ? it->get<double>() : 0;
}

const ordered_json* median_of(const ordered_json& record) {
  const auto t = record.find("time_ms");
  if (t == record.end() || !t->is_object()) return nullptr;
  const auto m = t->find("median");
  return m != t->end() && m->is_number() ? &*m : nullptr;
}

// The error figure a cell shows: what made it fail first (leaks, false shadows, misses), else
// the figure the plots use when it is not zero. Empty for a clean record.
std::string key_error(const ReportRecord& r, const ordered_json& record) {
  const auto error = record.find("error");
  if (error == record.end() || !error->is_object()) return "";
  std::string out;
  auto add = [&](const char* key, const char* name) {
    const double v = number_at(*error, key);
    if (v == 0) return;
    if (!out.empty()) out += " · ";
    out += display_number(v) + " " + name;
  };
  add("leaks", "leaks");
  add("false_shadows", "false");
  add("completeness_misses", "misses");
  add("unsound_listings", "unsound");
  if (!out.empty()) return out;
  if (r.output == "hard") return "";  // no robust mismatch: nothing more to say at a glance
  const std::optional<ErrorFigure> figure = plotted_error(r.output, *error);
  if (!figure || figure->value == 0) return "";
  std::string name = figure->key == "mean_abs_error"   ? "mean |e|"
                     : figure->key == "lighting_ratio" ? "lighting/exact"
                                                       : figure->key;
  return name + " " + display_number(figure->value);
}

std::vector<MatrixRow> matrix_rows(const ReportData& data) {
  std::vector<MatrixRow> rows;
  std::map<std::string, std::size_t> row_of;
  for (std::size_t ci = 0; ci < data.cases.size(); ++ci)
    for (std::size_t ri = 0; ri < data.cases[ci].records.size(); ++ri) {
      const ReportRecord& r = data.cases[ci].records[ri];
      // Keyed by output kind too, so that one label never holds two records of a case.
      auto [it, inserted] = row_of.try_emplace(r.output + " " + r.label(), rows.size());
      if (inserted)
        rows.push_back(MatrixRow{r.label(), r.algorithm,
                                 std::vector<const ReportRecord*>(data.cases.size(), nullptr),
                                 std::vector<std::size_t>(data.cases.size(), 0)});
      rows[it->second].cells[ci] = &r;
      rows[it->second].record_index[ci] = ri;
    }
  return rows;
}

bool all_not_supported(const MatrixRow& row) {
  for (const ReportRecord* r : row.cells)
    if (r && r->versions.back().json.value("verdict", "") != "NotSupported") return false;
  return true;
}

std::string cell_html(const MatrixRow& row, std::size_t ci) {
  const ReportRecord* r = row.cells[ci];
  if (!r) return "<td class=\"cell none\"></td>";
  const ordered_json& record = r->versions.back().json;
  const std::string verdict = record.value("verdict", "");
  std::string figures;
  if (verdict == "NotSupported") {
    figures = "n/s";
  } else {
    if (const ordered_json* median = median_of(record))
      figures = display_ms(median->get<double>()) + " ms";
    const std::string error = key_error(*r, record);
    if (!error.empty()) figures += "<br><span class=\"err\">" + html_escape(error) + "</span>";
    if (verdict == "Crash" || verdict == "Timeout")
      figures = html_escape(verdict) + (figures.empty() ? "" : "<br>" + figures);
  }
  // Runs side by side: a verdict that differs from the first directory's is outlined.
  const std::string first = r->versions.front().json.value("verdict", "");
  const bool changed = first != verdict;
  return "<td class=\"cell m-" + verdict_class(verdict) + (changed ? " changed-verdict" : "") +
         "\" data-record=\"" + html_escape(r->name) + "\" data-verdict=\"" + html_escape(verdict) +
         "\" title=\"" +
         html_escape(r->name + ": " + verdict + " — " + record.value("reason", "") +
                     (record.contains("known_limit")
                          ? " (a known limit: " + record.value("known_limit", "") + ")"
                          : "") +
                     (changed ? " (was " + first + ")" : "")) +
         "\"><a href=\"#" + record_anchor(ci, row.record_index[ci]) + "\">" + figures + "</a></td>";
}

// Folded rows: per algorithm, its labels and each distinct reason with the number of cases.
std::string folded_html(const std::vector<const MatrixRow*>& folded) {
  if (folded.empty()) return "";
  std::vector<std::string> algorithms;
  std::map<std::string, std::vector<const MatrixRow*>> by_algorithm;
  for (const MatrixRow* row : folded) {
    if (!by_algorithm.count(row->algorithm)) algorithms.push_back(row->algorithm);
    by_algorithm[row->algorithm].push_back(row);
  }
  std::string out =
      "<p class=\"legend-title\">NotSupported on every case (not in the matrix)</p>\n"
      "<ul class=\"not-supported\">\n";
  for (const std::string& algorithm : algorithms) {
    std::vector<std::string> reasons;
    std::map<std::string, std::size_t> count;
    std::string labels;
    for (const MatrixRow* row : by_algorithm[algorithm]) {
      labels += (labels.empty() ? "" : ", ") + row->label;
      for (const ReportRecord* r : row->cells) {
        if (!r) continue;
        const std::string reason = r->versions.back().json.value("reason", "");
        if (!count.count(reason)) reasons.push_back(reason);
        ++count[reason];
      }
    }
    out += "<li data-algorithm=\"" + html_escape(algorithm) + "\"><span class=\"verdict\">" +
           html_escape(algorithm) + "</span> (" + html_escape(labels) + "): ";
    for (std::size_t i = 0; i < reasons.size(); ++i)
      out += (i ? "; " : "") + html_escape(reasons[i]) + " <span class=\"count\">(" +
             std::to_string(count[reasons[i]]) + (count[reasons[i]] == 1 ? " record" : " records") +
             ")</span>";
    out += "</li>\n";
  }
  return out + "</ul>\n";
}

}  // namespace

std::string record_anchor(std::size_t case_index, std::size_t record_index) {
  return "record-" + std::to_string(case_index) + "-" + std::to_string(record_index);
}

std::string verdict_matrix_html(const ReportData& data) {
  const std::vector<MatrixRow> rows = matrix_rows(data);
  std::vector<const MatrixRow*> shown, folded;
  for (const MatrixRow& row : rows) (all_not_supported(row) ? folded : shown).push_back(&row);
  std::string out = "<h2>Verdicts</h2>\n";
  if (data.has_comparisons())
    out += "<p class=\"reason\">A record in several directories shows its last version.</p>\n";
  out += "<div class=\"matrix-wrap\"><table id=\"verdict-matrix\">\n<thead><tr><th></th>";
  for (std::size_t ci = 0; ci < data.cases.size(); ++ci)
    out += "<th class=\"case\"><a href=\"#case-" + std::to_string(ci) + "\">" +
           html_escape(data.cases[ci].name) + "</a></th>";
  out += "</tr></thead>\n<tbody>\n";
  for (const MatrixRow* row : shown) {
    out += "<tr data-label=\"" + html_escape(row->label) + "\"><th>" + html_escape(row->label) +
           "</th>";
    for (std::size_t ci = 0; ci < data.cases.size(); ++ci) out += cell_html(*row, ci);
    out += "</tr>\n";
  }
  out += "</tbody>\n</table></div>\n";
  return out + folded_html(folded);
}

std::vector<Plot> overview_plots(const ReportData& data) {
  struct Kind {
    const char* output;
    const char* what;
  };
  static const Kind kinds[] = {
      {"hard", "hard shadows"}, {"soft", "soft shadows"}, {"lights", "light assignment"}};
  std::vector<Plot> plots;
  for (const Kind& kind : kinds) {
    std::vector<std::string> algorithms;
    std::vector<PlotPoint> points;
    std::vector<std::size_t> series_of;
    std::set<std::string> keys;
    for (const ReportCase& c : data.cases)
      for (const ReportRecord& r : c.records) {
        if (r.output != kind.output) continue;
        const ordered_json& record = r.versions.back().json;
        // Only judged answers: NotSupported had nothing to judge, a crash gave no answer.
        const std::string verdict = record.value("verdict", "");
        if (verdict == "NotSupported" || verdict == "Crash" || verdict == "Timeout") continue;
        const ordered_json* median = median_of(record);
        const auto error = record.find("error");
        if (!median || median->get<double>() <= 0 || error == record.end()) continue;
        const std::optional<ErrorFigure> figure = plotted_error(r.output, *error);
        if (!figure || !std::isfinite(figure->value) || figure->value < 0) continue;
        keys.insert(figure->key);
        auto at = std::find(algorithms.begin(), algorithms.end(), r.algorithm);
        if (at == algorithms.end()) at = algorithms.insert(at, r.algorithm);
        series_of.push_back(std::size_t(at - algorithms.begin()));
        PlotPoint p;
        p.x = median->get<double>();
        p.y = figure->value;
        p.record = r.name;
        p.title = r.label() + " on " + c.name + ": " + display_ms(p.x) + " ms, " + figure->key +
                  " " + display_number(p.y) + " (" + record.value("verdict", "") + ")";
        points.push_back(std::move(p));
      }
    if (points.empty()) continue;
    double smallest = 0;
    for (const PlotPoint& p : points)
      if (p.y > 0 && (smallest == 0 || p.y < smallest)) smallest = p.y;
    const double zero_at =
        smallest > 0 ? std::pow(10.0, std::floor(std::log10(smallest)) - 1) : 1e-6;
    Plot plot;
    plot.css_class = "overview";
    plot.case_name = "";
    plot.title = std::string("All cases, ") + kind.what + ": error against run time";
    std::string key = keys.size() == 1 ? *keys.begin() : "error";
    if (key == "robust_mismatch_rate") key = "robust mismatch rate";
    if (key == "mean_abs_error") key = "mean |e|";
    if (key == "lighting_ratio") key = "lighting computations / exact";
    plot.x = PlotAxis{"median time [ms], log scale", true, false, false};
    plot.y =
        PlotAxis{key + ", log (0 drawn at " + display_number(zero_at) + ")", true, false, false};
    plot.empty_message = "no timed record with an error figure";
    for (std::size_t a = 0; a < algorithms.size(); ++a)
      plot.series.push_back(PlotSeries{algorithms[a], a, MarkerShape::circle, false, {}});
    std::vector<TimeErrorPoint> front_input;
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (points[i].y == 0) points[i].y = zero_at;
      front_input.push_back(TimeErrorPoint{points[i].x, points[i].y});
      plot.series[series_of[i]].points.push_back(points[i]);
    }
    for (std::size_t i : pareto_front(front_input)) plot.front.push_back(points[i]);
    plots.push_back(std::move(plot));
  }
  return plots;
}

}  // namespace shadowcts
