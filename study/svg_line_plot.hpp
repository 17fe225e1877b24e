#pragma once
// A line chart as SVG text. Hand-written: Debian has no C++ plotting library worth the dependency
// (the candidates pull in Python, Qt or gnuplot at run time), and a line chart is ~150 lines.
#include <string>
#include <utility>
#include <vector>

namespace rtmot::study {

struct LineSeries {
  std::string name;
  std::vector<std::pair<double, double>> points;  // (x, y), x ascending
  bool emphasised{false};                         // drawn thicker (e.g. the presets)
};

struct LinePlot {
  std::string title;
  std::string x_label;
  std::string y_label;
  std::vector<double> x_ticks;  // also where the x axis starts and ends
  bool log_x{false};
  std::vector<LineSeries> series;
};

/// A complete SVG document: axes with ticks, labels, one coloured polyline with markers per
/// series and a legend to the right.
std::string render_svg(const LinePlot& plot);

}  // namespace rtmot::study
