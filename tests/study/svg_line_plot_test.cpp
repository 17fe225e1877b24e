#include "study/svg_line_plot.hpp"

#include <gtest/gtest.h>

#include <string>

namespace rtmot::study {
namespace {

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

LinePlot two_series() {
  LinePlot plot;
  plot.title = "MOTA <vs> interval";
  plot.x_label = "interval";
  plot.y_label = "MOTA (%)";
  plot.x_ticks = {1, 2, 5, 10};
  plot.log_x = true;
  plot.series.push_back({"kalman-iou", {{1, 40.0}, {2, 38.0}, {5, 30.0}, {10, 20.0}}, false});
  plot.series.push_back({"preset-rtmot", {{1, 44.0}, {2, 43.0}, {5, 41.0}, {10, 35.0}}, true});
  return plot;
}

TEST(SvgLinePlot, DrawsOneLineAndOneLegendEntryPerSeries) {
  const std::string svg = render_svg(two_series());
  EXPECT_EQ(svg.rfind("<svg", 0), 0U);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  EXPECT_EQ(count(svg, "<polyline"), 2);
  EXPECT_EQ(count(svg, "<circle"), 8);
  EXPECT_NE(svg.find(">kalman-iou</text>"), std::string::npos);
  EXPECT_NE(svg.find(">preset-rtmot</text>"), std::string::npos);
  EXPECT_NE(svg.find("MOTA &lt;vs&gt; interval"), std::string::npos);  // escaped title
}

TEST(SvgLinePlot, HigherValuesAreDrawnHigherAndLogXSpacesTicksByRatio) {
  LinePlot plot = two_series();
  plot.series.resize(1);
  plot.series[0].points = {{1, 10.0}, {10, 50.0}};
  plot.x_ticks = {1, 10, 100};
  const std::string svg = render_svg(plot);
  const auto at = svg.find("points=\"") + 8;
  float x1 = 0, y1 = 0, x2 = 0, y2 = 0;
  ASSERT_EQ(std::sscanf(svg.c_str() + at, "%f,%f %f,%f", &x1, &y1, &x2, &y2), 4);
  EXPECT_LT(y2, y1);  // SVG's y grows downwards
  EXPECT_GT(x2, x1);
  // 10 is half way between 1 and 100 on a log axis: the plot area spans 70..620.
  EXPECT_NEAR(x2, 70 + (620 - 70) / 2.0, 0.2);
}

TEST(SvgLinePlot, SkipsNonFiniteValues) {
  LinePlot plot = two_series();
  plot.series[0].points[1].second = std::numeric_limits<double>::quiet_NaN();
  const std::string svg = render_svg(plot);
  EXPECT_EQ(svg.find("nan"), std::string::npos);
  EXPECT_EQ(count(svg, "<circle"), 7);
}

}  // namespace
}  // namespace rtmot::study
