#include "summary_table.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

#include "html_text.h"
#include "json_display.h"
#include "verdict_matrix.h"

namespace shadowcts {
namespace {

using nlohmann::ordered_json;

struct Cell {
  const ReportData& data;
  const ReportRecord& record;
  const Version& version;
  const Version* baseline;  // the record's first version, when this row is a later one
};

std::string data_attributes(const Cell& cell, const std::string& field, const std::string& value) {
  return " data-record=\"" + html_escape(cell.record.name) + "\" data-dir=\"" +
         std::to_string(cell.version.dir) + "\" data-field=\"" + html_escape(field) +
         "\" data-value=\"" + html_escape(value) + "\"";
}

// The value of a dotted field in a record, or nullptr.
const ordered_json* field_of(const ordered_json& record, const std::string& dotted) {
  const ordered_json* at = &record;
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = dotted.find('.', start);
    const std::string part = dotted.substr(start, dot - start);
    if (!at->is_object()) return nullptr;
    const auto it = at->find(part);
    if (it == at->end()) return nullptr;
    at = &*it;
    if (dot == std::string::npos) return at;
    start = dot + 1;
  }
}

// " changed" and a title naming the earlier value, when a later version differs from the first.
std::string change_marks(const Cell& cell, const std::string& field, const ordered_json& value,
                         std::string& title) {
  if (!cell.baseline) return "";
  const ordered_json* before = field_of(cell.baseline->json, field);
  if (before && *before == value) return "";
  title = " title=\"" +
          html_escape(cell.data.dirs[cell.baseline->dir].label + ": " +
                      (before ? display_value(*before) : std::string("absent"))) +
          "\"";
  return " changed";
}

std::string figures_html(const Cell& cell, const std::string& group) {
  const auto it = cell.version.json.find(group);
  if (it == cell.version.json.end() || !it->is_object()) return "";
  std::string out;
  for (const auto& [key, value] : flatten_fields(*it)) {
    // Lists of points are plotted below (mismatch curve), not tabulated.
    if (value->is_array() && !value->empty() && value->front().is_structured()) continue;
    const std::string field = group + "." + key;
    std::string title;
    const std::string changed = change_marks(cell, field, *value, title);
    std::string name = key;
    std::replace(name.begin(), name.end(), '_', ' ');
    out += "<span class=\"fig" + changed + "\"" + data_attributes(cell, field, exact_text(*value)) +
           title + "><span class=\"k\">" + html_escape(name) + "</span> " +
           html_escape(display_value(*value)) + "</span>";
  }
  return out;
}

// One time of a record, the whole call (field "time_ms") or a phase ("time_ms.phases.build"):
// its median, min–max over the runs and, in a later version, the ratio against the first.
std::string timing_html(const Cell& cell, const ordered_json& timing, const std::string& field,
                        const std::string& css_class, const std::string& label) {
  const auto median = timing.find("median");
  if (median == timing.end() || !median->is_number()) return "";
  std::string range_attributes, range_text;
  const auto runs = timing.find("runs");
  if (runs != timing.end() && runs->is_array() && !runs->empty()) {
    const ordered_json *lo = nullptr, *hi = nullptr;
    for (const ordered_json& run : *runs) {
      if (!run.is_number()) continue;
      if (!lo || run.get<double>() < lo->get<double>()) lo = &run;
      if (!hi || run.get<double>() > hi->get<double>()) hi = &run;
    }
    if (lo) {
      range_attributes = " data-min=\"" + html_escape(exact_text(*lo)) + "\" data-max=\"" +
                         html_escape(exact_text(*hi)) + "\" data-runs=\"" +
                         std::to_string(runs->size()) + "\"";
      range_text = " <span class=\"range\">(" + display_ms(lo->get<double>()) + "–" +
                   display_ms(hi->get<double>()) + ")</span>";
    }
  }
  // Times are noisy: a later version is marked only when it is more than 10% off.
  std::string ratio;
  if (cell.baseline) {
    const ordered_json* before = field_of(cell.baseline->json, field + ".median");
    if (before && before->is_number() && before->get<double>() > 0) {
      const double r = median->get<double>() / before->get<double>();
      char buffer[32];
      std::snprintf(buffer, sizeof buffer, "×%.2f", r);
      const char* trend = r < 0.9 ? " faster" : r > 1.1 ? " slower" : "";
      ratio = std::string(" <span class=\"ratio") + trend + "\" title=\"" +
              html_escape((label.empty() ? "" : label + " ") + "median against " +
                          cell.data.dirs[cell.baseline->dir].label) +
              "\">" + buffer + "</span>";
    }
  }
  const std::string name =
      label.empty() ? "" : "<span class=\"k\">" + html_escape(label) + "</span> ";
  return "<span class=\"" + css_class + "\"" +
         data_attributes(cell, field + ".median", exact_text(*median)) + range_attributes + ">" +
         name + display_ms(median->get<double>()) + range_text + ratio + "</span>";
}

std::string time_html(const Cell& cell) {
  const auto t = cell.version.json.find("time_ms");
  if (t == cell.version.json.end() || !t->is_object()) return "";
  std::string out = timing_html(cell, *t, "time_ms", "time", "");
  // The phases the algorithm times inside each run (build, query, ...), one line each.
  const auto phases = t->find("phases");
  if (phases != t->end() && phases->is_object())
    for (auto it = phases->begin(); it != phases->end(); ++it)
      if (it->is_object())
        out += timing_html(cell, *it, "time_ms.phases." + it.key(), "phase", it.key());
  return out;
}

}  // namespace

std::string verdict_class(const std::string& verdict) {
  std::string out;
  for (const char ch : verdict)
    if (std::isalnum(static_cast<unsigned char>(ch))) out += ch;
  return out;
}

std::string summary_table_html(const ReportData& data) {
  const bool several_dirs = data.dirs.size() > 1;
  std::string out =
      "<table class=\"summary\">\n<thead><tr><th>case</th><th>algorithm:variant "
      "[backend]</th>" +
      std::string(several_dirs ? "<th style=\"width: 8%\">directory</th>" : "") +
      "<th style=\"width: 9%\">verdict</th><th style=\"width: 13%\">median ms (min–max); "
      "build, query</th>"
      "<th style=\"width: 22%\">error</th><th>counters</th></tr></thead>\n"
      "<tbody>\n";
  for (std::size_t ci = 0; ci < data.cases.size(); ++ci) {
    const ReportCase& c = data.cases[ci];
    for (std::size_t ri = 0; ri < c.records.size(); ++ri) {
      const ReportRecord& r = c.records[ri];
      for (std::size_t vi = 0; vi < r.versions.size(); ++vi) {
        const Version& v = r.versions[vi];
        const Cell cell{data, r, v, vi > 0 ? &r.versions.front() : nullptr};
        const std::string verdict = v.json.value("verdict", "");
        std::string verdict_title;
        const std::string verdict_changed =
            change_marks(cell, "verdict", v.json.at("verdict"), verdict_title);
        const bool compared = r.versions.size() > 1;
        // The first version's row is what the verdict matrix links to.
        out += std::string("<tr") + (vi == 0 ? " id=\"" + record_anchor(ci, ri) + "\"" : "") +
               " class=\"record" + (compared ? " compared" : "") +
               (vi == 0 ? " first-version" : "") + "\">";
        out +=
            "<td><a href=\"#case-" + std::to_string(ci) + "\">" + html_escape(c.name) + "</a></td>";
        out += "<td title=\"" + html_escape(r.name) + "\">" + html_escape(r.label()) + "</td>";
        if (several_dirs) {
          out += "<td class=\"dir\">" + html_escape(data.dirs[v.dir].label);
          if (!compared) out += " <span class=\"only\">(only here)</span>";
          out += "</td>";
        }
        const std::string limit = v.json.value("known_limit", "");
        const std::string reason =
            html_escape(v.json.value("reason", "")) +
            (limit.empty()
                 ? ""
                 : "<div class=\"known-limit\">a known limit: " + html_escape(limit) + "</div>");
        // A Pass's reason repeats its figures: it goes to the hover text. Others show theirs.
        const bool quiet = verdict == "Pass" && verdict_title.empty();
        out += "<td class=\"verdict v-" + verdict_class(verdict) + verdict_changed + "\"" +
               data_attributes(cell, "verdict", verdict) +
               (quiet ? " title=\"" + reason + "\"" : verdict_title) + ">" + html_escape(verdict) +
               (quiet || verdict == "NotSupported" ? ""
                                                   : "<div class=\"reason\">" + reason + "</div>") +
               "</td>";
        if (verdict == "NotSupported") {
          // Nothing ran: one line with the reason instead of empty figures.
          out += "<td colspan=\"3\" class=\"reason\">" + reason + "</td></tr>\n";
          continue;
        }
        out += "<td class=\"num\">" + time_html(cell) + "</td>";
        out += "<td class=\"figs error\">" + figures_html(cell, "error") + "</td>";
        out += "<td class=\"figs counters\">" + figures_html(cell, "counters") + "</td>";
        out += "</tr>\n";
      }
    }
  }
  return out + "</tbody>\n</table>\n";
}

}  // namespace shadowcts
