#include "case_plots.h"

#include <algorithm>
#include <set>

#include "json_display.h"
#include "pareto_front.h"

namespace shadowcts {
namespace {

using nlohmann::ordered_json;

bool contains(const std::string& text, const char* part) {
  return text.find(part) != std::string::npos;
}

MarkerShape marker_of_dir(std::size_t dir) {
  static const MarkerShape shapes[] = {MarkerShape::circle, MarkerShape::square,
                                       MarkerShape::triangle, MarkerShape::diamond};
  return shapes[dir % 4];
}

bool ran(const ReportRecord& r) {
  for (const Version& v : r.versions)
    if (v.json.contains("time_ms")) return true;
  return false;
}

// Colours stand for algorithms (in order of first appearance among the records of the case that
// ran), so a family's variants read as one colour; the hover text names the variant.
std::size_t colour_of_algorithm(const ReportCase& c, const std::string& algorithm) {
  std::vector<std::string> seen;
  for (const ReportRecord& r : c.records) {
    if (!ran(r)) continue;
    if (r.algorithm == algorithm) break;
    if (std::find(seen.begin(), seen.end(), r.algorithm) == seen.end()) seen.push_back(r.algorithm);
  }
  return seen.size();
}

std::string series_name(const ReportData& data, const ReportRecord& r, std::size_t dir) {
  return data.dirs.size() > 1 ? r.label() + " — " + data.dirs[dir].label : r.label();
}

const ordered_json* median_time(const ordered_json& record) {
  const auto t = record.find("time_ms");
  if (t == record.end() || !t->is_object()) return nullptr;
  const auto m = t->find("median");
  return m != t->end() && m->is_number() ? &*m : nullptr;
}

}  // namespace

std::optional<ErrorFigure> plotted_error(const std::string& output, const ordered_json& error) {
  const auto fields = flatten_fields(error);
  auto first = [&](bool (*wanted)(const std::string&)) -> std::optional<ErrorFigure> {
    for (const auto& [key, value] : fields)
      if (value->is_number() && wanted(key)) return ErrorFigure{key, value->get<double>()};
    return std::nullopt;
  };
  std::optional<ErrorFigure> figure;
  if (output == "hard")
    figure = first([](const std::string& k) { return k == "robust_mismatch_rate"; });
  else if (output == "soft")
    figure = first([](const std::string& k) { return k == "mean_abs_error"; });
  else if (output == "lights")
    figure = first(
        [](const std::string& k) { return k == "lighting_ratio" || contains(k, "overhead"); });
  if (!figure)
    figure = first([](const std::string& k) {
      return contains(k, "error") || contains(k, "rate") || contains(k, "overhead");
    });
  if (!figure) figure = first([](const std::string&) { return true; });
  return figure;
}

Plot error_against_time_plot(const ReportData& data, const ReportCase& c) {
  Plot plot;
  plot.css_class = "error-vs-time";
  plot.case_name = c.name;
  plot.title = "Error against run time — " + c.name;
  plot.x = PlotAxis{"median time [ms], log scale", true, false, false};
  plot.y = PlotAxis{"error", false, false, true};
  plot.empty_message = "no timed result with an error figure in this case";

  std::set<std::string> error_keys;
  std::vector<TimeErrorPoint> all;
  std::vector<PlotPoint> all_points;
  for (std::size_t i = 0; i < c.records.size(); ++i) {
    const ReportRecord& r = c.records[i];
    for (const Version& v : r.versions) {
      const ordered_json* time = median_time(v.json);
      const auto error = v.json.find("error");
      if (!time || error == v.json.end()) continue;
      const std::optional<ErrorFigure> figure = plotted_error(r.output, *error);
      if (!figure) continue;
      error_keys.insert(figure->key);
      PlotPoint p;
      p.x = time->get<double>();
      p.y = figure->value;
      p.record = r.name;
      p.title = series_name(data, r, v.dir) + ": " + display_ms(p.x) + " ms, " + figure->key + " " +
                display_number(p.y) + " (" + v.json.value("verdict", "") + ")";
      PlotSeries s{series_name(data, r, v.dir),
                   colour_of_algorithm(c, r.algorithm),
                   marker_of_dir(v.dir),
                   false,
                   {p}};
      plot.series.push_back(std::move(s));
      all.push_back(TimeErrorPoint{p.x, p.y});
      all_points.push_back(p);
    }
  }
  if (error_keys.size() == 1)
    plot.y.label = *error_keys.begin();
  else if (error_keys.size() > 1)
    plot.y.label = "error (figure per output kind; see hover text)";
  // Non-positive times cannot lie on the log axis; they stay off the front as well.
  std::vector<TimeErrorPoint> drawable;
  std::vector<std::size_t> drawable_index;
  for (std::size_t i = 0; i < all.size(); ++i)
    if (all[i].time > 0) {
      drawable.push_back(all[i]);
      drawable_index.push_back(i);
    }
  for (std::size_t i : pareto_front(drawable)) plot.front.push_back(all_points[drawable_index[i]]);
  return plot;
}

std::optional<Plot> mismatch_curve_plot(const ReportData& data, const ReportCase& c) {
  Plot plot;
  plot.css_class = "mismatch-curve";
  plot.case_name = c.name;
  plot.title = "Robust mismatches against eps_rel — " + c.name;
  plot.x = PlotAxis{"eps_rel (half-width of the ambiguity band)", false, true, false};
  plot.y = PlotAxis{"robust mismatches", false, false, true};
  plot.empty_message = "no curve point can be drawn";
  for (std::size_t i = 0; i < c.records.size(); ++i) {
    const ReportRecord& r = c.records[i];
    for (const Version& v : r.versions) {
      const auto error = v.json.find("error");
      if (error == v.json.end() || !error->is_object()) continue;
      const auto curve = error->find("mismatch_curve");
      if (curve == error->end() || !curve->is_array()) continue;
      PlotSeries s{series_name(data, r, v.dir),
                   colour_of_algorithm(c, r.algorithm),
                   marker_of_dir(v.dir),
                   true,
                   {}};
      for (const ordered_json& point : *curve) {
        const auto x = point.find("eps_rel_log2"), y = point.find("robust_mismatches");
        if (x == point.end() || y == point.end() || !x->is_number() || !y->is_number()) continue;
        PlotPoint p;
        p.x = x->get<double>();
        p.y = y->get<double>();
        p.record = r.name;
        p.title = s.name + ": eps_rel 2^" + display_number(p.x) + ", " + display_number(p.y) +
                  " robust mismatches";
        s.points.push_back(std::move(p));
      }
      if (!s.points.empty()) plot.series.push_back(std::move(s));
    }
  }
  if (plot.series.empty()) return std::nullopt;
  return plot;
}

}  // namespace shadowcts
