#include "svg_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "html_text.h"

namespace shadowcts {
namespace {

// Layout in SVG user units.
constexpr double plot_left = 72, plot_top = 34, plot_width = 420, plot_height = 230;
constexpr double svg_width = 520, legend_row = 16;

std::string fixed(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.2f", v);
  return buffer;
}

std::string tick_text(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", v);
  return buffer;
}

// The range an axis maps, in axis units (log10 of the value for log axes), and its ticks.
struct AxisScale {
  double lo = 0, hi = 1;
  std::vector<double> ticks;
  bool log10 = false;

  double unit(double v) const { return log10 ? std::log10(v) : v; }
  double fraction(double v) const { return (unit(v) - lo) / (hi - lo); }
};

bool drawable(const PlotAxis& axis, double v) {
  return std::isfinite(v) && (!axis.log10 || v > 0);
}

AxisScale scale_for(const PlotAxis& axis, const std::vector<double>& values) {
  AxisScale s;
  s.log10 = axis.log10;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (double v : values) {
    lo = std::min(lo, s.unit(v));
    hi = std::max(hi, s.unit(v));
  }
  if (values.empty()) lo = hi = 0;
  if (axis.log10) {
    // Whole decades, at least one.
    s.lo = std::floor(lo);
    s.hi = std::max(std::ceil(hi), s.lo + 1);
    for (double k = s.lo; k <= s.hi; ++k) s.ticks.push_back(std::pow(10.0, k));
    return s;
  }
  if (axis.include_zero) {
    lo = std::min(lo, 0.0);
    hi = std::max(hi, 0.0);
  }
  if (hi - lo <= 0) {
    // One value: a unit range above it (a zero error shows as the bottom of a 0..1 axis).
    hi = lo + (lo == 0 ? 1 : std::fabs(lo));
  }
  // Nice step: 1, 2 or 5 times a power of ten, giving at most about six intervals.
  const double raw = (hi - lo) / 6;
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  double step = decade;
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * decade >= raw) {
      step = m * decade;
      break;
    }
  if (axis.powers_of_two) step = std::max(step, 1.0);  // integer exponents only
  // The tolerance keeps a bound that is a multiple of the step (up to rounding) as the end.
  s.lo = std::floor(lo / step + 1e-9) * step;
  s.hi = std::ceil(hi / step - 1e-9) * step;
  for (double t = s.lo; t <= s.hi + step / 2; t += step)
    s.ticks.push_back(std::abs(t) < step * 1e-9 ? 0 : t);
  return s;
}

std::string marker_svg(MarkerShape shape, double x, double y, const char* colour, double size) {
  std::ostringstream out;
  switch (shape) {
    case MarkerShape::circle:
      out << "<circle cx=\"" << fixed(x) << "\" cy=\"" << fixed(y) << "\" r=\"" << fixed(size)
          << "\" fill=\"" << colour << "\"";
      break;
    case MarkerShape::square:
      out << "<rect x=\"" << fixed(x - size) << "\" y=\"" << fixed(y - size) << "\" width=\""
          << fixed(2 * size) << "\" height=\"" << fixed(2 * size) << "\" fill=\"" << colour << "\"";
      break;
    case MarkerShape::triangle:
      out << "<polygon points=\"" << fixed(x) << "," << fixed(y - 1.2 * size) << " "
          << fixed(x + 1.1 * size) << "," << fixed(y + 0.9 * size) << " " << fixed(x - 1.1 * size)
          << "," << fixed(y + 0.9 * size) << "\" fill=\"" << colour << "\"";
      break;
    case MarkerShape::diamond:
      out << "<polygon points=\"" << fixed(x) << "," << fixed(y - 1.3 * size) << " "
          << fixed(x + 1.3 * size) << "," << fixed(y) << " " << fixed(x) << ","
          << fixed(y + 1.3 * size) << " " << fixed(x - 1.3 * size) << "," << fixed(y)
          << "\" fill=\"" << colour << "\"";
      break;
  }
  return out.str();
}

std::string tick_label(const PlotAxis& axis, double v) {
  if (axis.powers_of_two) return "2<tspan dy=\"-5\" font-size=\"9\">" + tick_text(v) + "</tspan>";
  return html_escape(tick_text(v));
}

}  // namespace

const char* series_colour(std::size_t index) {
  // Okabe-Ito, without its yellow (too faint on white).
  static const char* const palette[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                        "#E69F00", "#56B4E9", "#000000"};
  return palette[index % (sizeof palette / sizeof palette[0])];
}

std::string render_svg_plot(const Plot& plot) {
  std::vector<double> xs, ys;
  std::size_t left_out = 0;
  for (const PlotSeries& s : plot.series)
    for (const PlotPoint& p : s.points) {
      if (drawable(plot.x, p.x) && drawable(plot.y, p.y)) {
        xs.push_back(p.x);
        ys.push_back(p.y);
      } else {
        ++left_out;
      }
    }
  const AxisScale sx = scale_for(plot.x, xs), sy = scale_for(plot.y, ys);
  auto px = [&](double x) { return plot_left + sx.fraction(x) * plot_width; };
  auto py = [&](double y) { return plot_top + (1 - sy.fraction(y)) * plot_height; };

  // Long legends go into two columns.
  const std::size_t legend_columns = plot.series.size() > 8 ? 2 : 1;
  const std::size_t legend_rows = (plot.series.size() + legend_columns - 1) / legend_columns;
  const double legend_top = plot_top + plot_height + 48;
  const double svg_height = legend_top + legend_row * double(legend_rows + 1) + 6;
  std::ostringstream out;
  out << "<svg class=\"plot " << html_escape(plot.css_class) << "\" data-case=\""
      << html_escape(plot.case_name) << "\" xmlns=\"http://www.w3.org/2000/svg\" width=\""
      << fixed(svg_width) << "\" height=\"" << fixed(svg_height) << "\" viewBox=\"0 0 "
      << fixed(svg_width) << " " << fixed(svg_height) << "\" role=\"img\">\n";
  out << "<title>" << html_escape(plot.title) << "</title>\n";
  out << "<text x=\"" << fixed(plot_left) << "\" y=\"18\" class=\"plot-title\">"
      << html_escape(plot.title) << "</text>\n";
  out << "<rect x=\"" << fixed(plot_left) << "\" y=\"" << fixed(plot_top) << "\" width=\""
      << fixed(plot_width) << "\" height=\"" << fixed(plot_height)
      << "\" fill=\"#fbfbfb\" stroke=\"#999\"/>\n";

  // Grid and tick labels.
  for (double t : sx.ticks) {
    const double x = px(t);
    out << "<line x1=\"" << fixed(x) << "\" y1=\"" << fixed(plot_top) << "\" x2=\"" << fixed(x)
        << "\" y2=\"" << fixed(plot_top + plot_height) << "\" class=\"grid\"/>"
        << "<text x=\"" << fixed(x) << "\" y=\"" << fixed(plot_top + plot_height + 15)
        << "\" text-anchor=\"middle\" class=\"tick\">" << tick_label(plot.x, t) << "</text>\n";
  }
  for (double t : sy.ticks) {
    const double y = py(t);
    out << "<line x1=\"" << fixed(plot_left) << "\" y1=\"" << fixed(y) << "\" x2=\""
        << fixed(plot_left + plot_width) << "\" y2=\"" << fixed(y) << "\" class=\"grid\"/>"
        << "<text x=\"" << fixed(plot_left - 6) << "\" y=\"" << fixed(y + 4)
        << "\" text-anchor=\"end\" class=\"tick\">" << tick_label(plot.y, t) << "</text>\n";
  }
  out << "<text x=\"" << fixed(plot_left + plot_width / 2) << "\" y=\""
      << fixed(plot_top + plot_height + 34) << "\" text-anchor=\"middle\" class=\"axis-label\">"
      << html_escape(plot.x.label) << "</text>\n";
  out << "<text transform=\"translate(16 " << fixed(plot_top + plot_height / 2)
      << ") rotate(-90)\" text-anchor=\"middle\" class=\"axis-label\">" << html_escape(plot.y.label)
      << "</text>\n";

  // Pareto front: a dashed staircase under the points, rings drawn over them.
  std::vector<const PlotPoint*> front;
  for (const PlotPoint& p : plot.front)
    if (drawable(plot.x, p.x) && drawable(plot.y, p.y)) front.push_back(&p);
  if (front.size() > 1) {
    out << "<polyline class=\"pareto-front\" fill=\"none\" stroke=\"#444\" stroke-dasharray=\"4 "
           "3\" "
           "points=\"";
    for (std::size_t i = 0; i < front.size(); ++i) {
      if (i > 0) out << fixed(px(front[i]->x)) << "," << fixed(py(front[i - 1]->y)) << " ";
      out << fixed(px(front[i]->x)) << "," << fixed(py(front[i]->y))
          << (i + 1 < front.size() ? " " : "");
    }
    out << "\"/>\n";
  }

  for (const PlotSeries& s : plot.series) {
    const char* colour = series_colour(s.colour);
    std::vector<const PlotPoint*> drawn;
    for (const PlotPoint& p : s.points)
      if (drawable(plot.x, p.x) && drawable(plot.y, p.y)) drawn.push_back(&p);
    if (s.connect && drawn.size() > 1) {
      out << "<polyline fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"1.5\" points=\"";
      for (std::size_t i = 0; i < drawn.size(); ++i)
        out << (i ? " " : "") << fixed(px(drawn[i]->x)) << "," << fixed(py(drawn[i]->y));
      out << "\"/>\n";
    }
    for (const PlotPoint* p : drawn) {
      out << "<g class=\"point\" data-record=\"" << html_escape(p->record) << "\">"
          << marker_svg(s.marker, px(p->x), py(p->y), colour, s.connect ? 3 : 4.5) << "><title>"
          << html_escape(p->title) << "</title>"
          << (s.marker == MarkerShape::circle   ? "</circle>"
              : s.marker == MarkerShape::square ? "</rect>"
                                                : "</polygon>")
          << "</g>\n";
    }
  }
  for (const PlotPoint* p : front)
    out << "<circle class=\"pareto-point\" cx=\"" << fixed(px(p->x)) << "\" cy=\""
        << fixed(py(p->y))
        << "\" r=\"8\" fill=\"none\" stroke=\"#222\" stroke-width=\"1.2\"><title>"
        << html_escape("Pareto front: " + p->title) << "</title></circle>\n";

  if (xs.empty())
    out << "<text x=\"" << fixed(plot_left + plot_width / 2) << "\" y=\""
        << fixed(plot_top + plot_height / 2) << "\" text-anchor=\"middle\" class=\"empty\">"
        << html_escape(plot.empty_message) << "</text>\n";

  // Legend: one row per series, then the front's symbol and what was left out.
  for (std::size_t i = 0; i < plot.series.size(); ++i) {
    const PlotSeries& s = plot.series[i];
    const double x = 12 + double(i / legend_rows) * (svg_width - 12) / 2;
    const double y = legend_top + legend_row * double(i % legend_rows);
    out << marker_svg(s.marker, x + 6, y - 4, series_colour(s.colour), 4.5) << "/>"
        << "<text x=\"" << fixed(x + 18) << "\" y=\"" << fixed(y) << "\" class=\"legend\">"
        << html_escape(s.name) << "</text>\n";
  }
  const double row_y = legend_top + legend_row * double(legend_rows);
  std::string note;
  if (!front.empty()) note = "ringed, dashed: Pareto front (no point is both faster and better)";
  if (left_out > 0)
    note += (note.empty() ? "" : "; ") + std::to_string(left_out) +
            " point(s) not drawable on these axes";
  if (!note.empty())
    out << "<text x=\"12\" y=\"" << fixed(row_y) << "\" class=\"legend\">" << html_escape(note)
        << "</text>\n";
  out << "</svg>";
  return out.str();
}

}  // namespace shadowcts
