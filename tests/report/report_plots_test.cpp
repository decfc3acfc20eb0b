// The plots: the Pareto front, which error figure stands for a record, and the SVG itself.
#include <regex>

#include <gtest/gtest.h>

#include "case_plots.h"
#include "pareto_front.h"
#include "svg_plot.h"

namespace shadowcts {
namespace {

using nlohmann::ordered_json;

TEST(ParetoFront, KeepsThePointsNothingBeatsInBoth) {
  //   0: fast, bad   1: slow, good   2: dominated by 0 and 1   3: equal to 1   4: slowest, worst
  const std::vector<TimeErrorPoint> points = {{1, 0.5}, {10, 0}, {20, 0.6}, {10, 0}, {30, 1}};
  EXPECT_EQ(pareto_front(points), (std::vector<std::size_t>{0, 1, 3}));
  EXPECT_EQ(pareto_front({}), std::vector<std::size_t>{});
  EXPECT_EQ(pareto_front({{5, 5}}), std::vector<std::size_t>{0});
  // Same time, different error: only the better one.
  EXPECT_EQ(pareto_front({{2, 0.1}, {2, 0.2}}), std::vector<std::size_t>{0});
}

TEST(PlottedError, FollowsTheOutputKind) {
  const ordered_json hard = {{"compared", 10}, {"leaks", 1}, {"robust_mismatch_rate", 0.1}};
  EXPECT_EQ(plotted_error("hard", hard)->key, "robust_mismatch_rate");
  EXPECT_EQ(plotted_error("hard", hard)->value, 0.1);
  const ordered_json soft = {{"compared", 10}, {"rms_error", 0.3}, {"mean_abs_error", 0.2}};
  EXPECT_EQ(plotted_error("soft", soft)->key, "mean_abs_error");
  const ordered_json lights = {
      {"lists", 4}, {"lighting_computations", 90}, {"lighting_ratio", 1.8}};
  EXPECT_EQ(plotted_error("lights", lights)->key, "lighting_ratio");
  // A kind not known here: the first figure named like an error, else the first number.
  const ordered_json other = {{"label", "x"}, {"cells", 3}, {"nested", {{"max_error", 0.5}}}};
  EXPECT_EQ(plotted_error("volumes", other)->key, "nested.max_error");
  EXPECT_EQ(plotted_error("volumes", ordered_json{{"cells", 3}})->key, "cells");
  EXPECT_FALSE(plotted_error("hard", ordered_json{{"label", "x"}}).has_value());
  EXPECT_FALSE(plotted_error("hard", ordered_json()).has_value());
}

Plot sample_plot() {
  Plot plot;
  plot.css_class = "error-vs-time";
  plot.case_name = "c";
  plot.title = "t";
  plot.x = PlotAxis{"ms", true, false, false};
  plot.y = PlotAxis{"rate", false, false, true};
  plot.series = {
      PlotSeries{"fast", 0, MarkerShape::circle, false, {{0.5, 0.2, "fast", "r.fast"}}},
      PlotSeries{"slow", 1, MarkerShape::square, false, {{200, 0, "slow", "r.slow"}}},
      PlotSeries{"broken", 2, MarkerShape::triangle, false, {{0, 0, "zero time", "r.zero"}}}};
  plot.front = {plot.series[0].points[0], plot.series[1].points[0]};
  plot.empty_message = "nothing";
  return plot;
}

TEST(SvgPlot, DrawsLogDecadesPointsFrontAndLegend) {
  const std::string svg = render_svg_plot(sample_plot());
  EXPECT_EQ(svg.rfind("<svg class=\"plot error-vs-time\" data-case=\"c\"", 0), 0u);
  // x from 0.5 to 200 ms: decades 0.1 .. 1000.
  for (const char* tick : {">0.1<", ">1<", ">10<", ">100<", ">1000<"})
    EXPECT_NE(svg.find(tick), std::string::npos) << tick;
  EXPECT_EQ(svg.find(">0.01<"), std::string::npos);
  EXPECT_EQ(svg.find(">10000<"), std::string::npos);
  // Drawable points carry their record; the zero time cannot sit on a log axis and is said so.
  EXPECT_NE(svg.find("data-record=\"r.fast\"><circle"), std::string::npos);
  EXPECT_NE(svg.find("data-record=\"r.slow\"><rect"), std::string::npos);
  EXPECT_EQ(svg.find("data-record=\"r.zero\""), std::string::npos);
  EXPECT_NE(svg.find("1 point(s) not drawable"), std::string::npos);
  EXPECT_NE(svg.find("<title>fast</title>"), std::string::npos);
  // The front: two rings and a staircase through them.
  std::size_t rings = 0;
  for (std::size_t at = svg.find("class=\"pareto-point\""); at != std::string::npos;
       at = svg.find("class=\"pareto-point\"", at + 1))
    ++rings;
  EXPECT_EQ(rings, 2u);
  EXPECT_NE(svg.find("class=\"pareto-front\""), std::string::npos);
  EXPECT_NE(svg.find(">broken</text>"), std::string::npos);
  EXPECT_EQ(svg.find("nothing"), std::string::npos);
  EXPECT_EQ(render_svg_plot(sample_plot()), svg);
}

TEST(SvgPlot, PlacesPointsOnTheirAxes) {
  Plot plot = sample_plot();
  plot.series.pop_back();
  plot.front.clear();
  const std::string svg = render_svg_plot(plot);
  // Plot area x 72..492 over decades 0.1..1000 (four): 0.5 ms at (log10(5)) / 4 of the width.
  // y 34..264 over 0..0.2 (nice ticks reach 0.2 exactly): 0.2 at the top, 0 at the bottom.
  std::smatch m;
  ASSERT_TRUE(std::regex_search(
      svg, m, std::regex(R"re(r\.fast"><circle cx="([0-9.]+)" cy="([0-9.]+)")re")));
  EXPECT_NEAR(std::stod(m[1]), 72 + 420 * std::log10(5.0) / 4, 0.01);
  EXPECT_NEAR(std::stod(m[2]), 34, 0.01);
  ASSERT_TRUE(
      std::regex_search(svg, m, std::regex(R"re(r\.slow"><rect x="([0-9.]+)" y="([0-9.]+)")re")));
  EXPECT_NEAR(std::stod(m[1]) + 4.5, 72 + 420 * (std::log10(200.0) + 1) / 4, 0.01);
  EXPECT_NEAR(std::stod(m[2]) + 4.5, 264, 0.01);
}

TEST(SvgPlot, SaysWhenThereIsNothingToDraw) {
  Plot plot = sample_plot();
  plot.series.clear();
  plot.front.clear();
  const std::string svg = render_svg_plot(plot);
  EXPECT_NE(svg.find(">nothing</text>"), std::string::npos);
  EXPECT_EQ(svg.find("<g class=\"point\""), std::string::npos);
}

}  // namespace
}  // namespace shadowcts
