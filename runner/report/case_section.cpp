#include "case_section.h"

#include <algorithm>
#include <map>

#include "case_plots.h"
#include "colour_legends.h"
#include "html_text.h"
#include "json_display.h"
#include "svg_plot.h"

namespace shadowcts {
namespace {

using nlohmann::ordered_json;

bool ends_with(const std::string& text, const std::string& end) {
  return text.size() >= end.size() && text.compare(text.size() - end.size(), end.size(), end) == 0;
}

// Image paths the case summary names: keys ending in "image" (a path) or "images" (a list).
std::vector<std::pair<std::string, std::string>> case_images(const ordered_json& summary) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& [key, value] : flatten_fields(summary)) {
    if (ends_with(key, "image") && value->is_string())
      out.emplace_back(key, value->get<std::string>());
    if (ends_with(key, "images") && value->is_array())
      for (const ordered_json& path : *value)
        if (path.is_string()) out.emplace_back(key, path.get<std::string>());
  }
  return out;
}

bool is_image_field(const std::string& key) {
  return ends_with(key, "image") || ends_with(key, "images");
}

// Facts: one row per flattened key, one column per directory holding the case; a cell that differs
// from the first directory's is marked.
std::string facts_html(const ReportData& data, const ReportCase& c) {
  std::vector<std::string> keys;
  std::vector<std::map<std::string, const ordered_json*>> columns;
  for (const Version& v : c.summaries) {
    std::map<std::string, const ordered_json*> column;
    for (const auto& [key, value] : flatten_fields(v.json)) {
      if (key == "name" || key == "left_out" || is_image_field(key)) continue;
      if (!column.count(key) && std::find(keys.begin(), keys.end(), key) == keys.end())
        keys.push_back(key);
      column[key] = value;
    }
    columns.push_back(std::move(column));
  }
  if (columns.size() == 1) {
    // One directory: the facts as a wrapped line of figures, which takes little height.
    std::string out = "<div class=\"facts\">";
    for (const std::string& key : keys)
      out += "<span class=\"fig\"><span class=\"k\">" + html_escape(key) + "</span> " +
             html_escape(display_value(*columns[0].at(key))) + "</span>";
    return out + "</div>\n";
  }
  std::string out = "<table class=\"facts\">";
  {
    out += "<tr><th></th>";
    for (const Version& v : c.summaries)
      out += "<th>" + html_escape(data.dirs[v.dir].label) + "</th>";
    out += "</tr>";
  }
  for (const std::string& key : keys) {
    out += "<tr><th>" + html_escape(key) + "</th>";
    for (std::size_t i = 0; i < columns.size(); ++i) {
      const auto it = columns[i].find(key);
      const ordered_json* value = it == columns[i].end() ? nullptr : it->second;
      const auto first = columns[0].find(key);
      const bool differs =
          i > 0 && (first == columns[0].end() || !value || *first->second != *value);
      out += std::string("<td") + (differs ? " class=\"changed\"" : "") + ">" +
             (value ? html_escape(display_value(*value)) : "—") + "</td>";
    }
    out += "</tr>";
  }
  return out + "</table>\n";
}

std::string left_out_html(const ReportData& data, const ReportCase& c) {
  std::string out;
  for (const Version& v : c.summaries) {
    const auto it = v.json.find("left_out");
    if (it == v.json.end() || !it->is_array() || it->empty()) continue;
    out += "<div class=\"left-out\"><span class=\"legend-title\">left out";
    if (data.dirs.size() > 1) out += " (" + html_escape(data.dirs[v.dir].label) + ")";
    out += "</span><ul>";
    for (const ordered_json& line : *it) out += "<li>" + html_escape(display_value(line)) + "</li>";
    out += "</ul></div>\n";
  }
  return out;
}

std::string figure_html(const ReportData& data, std::size_t dir, const std::string& path,
                        const std::string& caption) {
  const std::string src = url_path(data.page_relative(dir, path));
  return "<figure><img src=\"" + html_escape(src) + "\" alt=\"" + html_escape(caption) +
         "\"><figcaption>" + html_escape(caption) + "</figcaption></figure>";
}

// "bruteforce.exact.reference.mismatch" from
// "images/<case>/bruteforce.exact.reference.mismatch.png"
std::string image_caption(const std::string& path) {
  std::string stem = std::filesystem::path(path).stem().string();
  return stem.empty() ? path : stem;
}

std::string images_html(const ReportData& data, const ReportCase& c) {
  std::string figures;
  bool any_hard = false;
  for (const Version& v : c.summaries)
    for (const auto& [key, path] : case_images(v.json)) {
      std::string caption = "oracle: " + image_caption(path);
      if (data.dirs.size() > 1) caption += " — " + data.dirs[v.dir].label;
      figures += figure_html(data, v.dir, path, caption);
    }
  if (!figures.empty())
    figures =
        "<div class=\"image-row\"><div class=\"row-label\">oracle</div>" + figures + "</div>\n";
  for (const ReportRecord& r : c.records) {
    std::string row;
    for (const Version& v : r.versions) {
      const auto images = v.json.find("images");
      if (images == v.json.end() || !images->is_array()) continue;
      for (const ordered_json& path : *images) {
        if (!path.is_string()) continue;
        std::string caption = image_caption(path.get<std::string>());
        if (data.dirs.size() > 1) caption += " — " + data.dirs[v.dir].label;
        row += figure_html(data, v.dir, path.get<std::string>(), caption);
      }
    }
    if (row.empty()) continue;
    any_hard |= r.output == "hard";
    figures += "<div class=\"image-row\"><div class=\"row-label\">" + html_escape(r.label()) +
               "</div>" + row + "</div>\n";
  }
  if (figures.empty()) return "";
  std::string legends;
  if (any_hard)
    legends = legend_html("mask", shadow_mask_legend()) +
              legend_html("mismatch map", mismatch_map_legend());
  return "<div class=\"images\">\n" + legends + figures + "</div>\n";
}

}  // namespace

std::string case_section_html(const ReportData& data, std::size_t case_index) {
  const ReportCase& c = data.cases[case_index];
  std::string out = "<section class=\"case\" id=\"case-" + std::to_string(case_index) +
                    "\" data-case=\"" + html_escape(c.name) + "\">\n<h2>" + html_escape(c.name) +
                    "</h2>\n";
  out += facts_html(data, c);
  out += left_out_html(data, c);
  out += "<div class=\"plots\">\n" + render_svg_plot(error_against_time_plot(data, c)) + "\n";
  if (const std::optional<Plot> curve = mismatch_curve_plot(data, c))
    out += render_svg_plot(*curve) + "\n";
  out += "</div>\n";
  out += images_html(data, c);
  return out + "</section>\n";
}

}  // namespace shadowcts
