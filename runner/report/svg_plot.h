#pragma once
// A small scatter/line plot written as inline SVG: axes with ticks (linear or log10), series with
// colour and marker shape, hover titles per point, an optional Pareto front, a legend below.
#include <cstddef>
#include <string>
#include <vector>

namespace shadowcts {

struct PlotPoint {
  double x = 0, y = 0;
  std::string title;   // hover text (<title>), plain text
  std::string record;  // written as data-record, so tests and tools can find the point
};

enum class MarkerShape { circle, square, triangle, diamond };

struct PlotSeries {
  std::string name;  // legend text, plain text
  std::size_t colour = 0;
  MarkerShape marker = MarkerShape::circle;
  bool connect = false;  // draw a line through the points in order
  std::vector<PlotPoint> points;
};

struct PlotAxis {
  std::string label;
  bool log10 = false;          // decades; non-positive values cannot be drawn
  bool powers_of_two = false;  // tick labels 2^k (values are the exponents k)
  bool include_zero = false;   // linear axes: the range reaches down (or up) to 0
};

struct Plot {
  std::string css_class;  // e.g. "error-vs-time"
  std::string case_name;  // written as data-case
  std::string title;
  PlotAxis x, y;
  std::vector<PlotSeries> series;
  // Points of the Pareto front (in x order): ringed, and joined by a dashed staircase.
  std::vector<PlotPoint> front;
  std::string empty_message;  // shown when no point can be drawn
};

// The plot as one <svg> element. Deterministic: same plot, same bytes.
std::string render_svg_plot(const Plot& plot);

// The colour of a series' index, from a palette that colour-blind readers can tell apart.
const char* series_colour(std::size_t index);

}  // namespace shadowcts
