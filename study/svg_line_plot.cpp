#include "study/svg_line_plot.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace rtmot::study {
namespace {

constexpr double kWidth = 900;
constexpr double kHeight = 480;
constexpr double kLeft = 70;
constexpr double kRight = 620;  // the legend lives to the right of this
constexpr double kTop = 40;
constexpr double kBottom = 420;

// Tableau 10: distinguishable, also for the common colour-vision deficiencies.
constexpr std::array<const char*, 10> kColours = {"#4e79a7", "#f28e2b", "#e15759", "#76b7b2",
                                                  "#59a14f", "#edc948", "#b07aa1", "#ff9da7",
                                                  "#9c755f", "#bab0ac"};
constexpr std::array<const char*, 3> kDashes = {"", "6,3", "2,3"};

std::string escaped(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// A "nice" step (1, 2 or 5 times a power of ten) giving about five ticks over `span`.
double tick_step(double span) {
  const double raw = span / 5.0;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  for (const double m : {1.0, 2.0, 5.0}) {
    if (m * power >= raw) return m * power;
  }
  return 10.0 * power;
}

}  // namespace

std::string render_svg(const LinePlot& plot) {
  double y_min = std::numeric_limits<double>::infinity();
  double y_max = -y_min;
  for (const auto& series : plot.series) {
    for (const auto& point : series.points) {
      if (!std::isfinite(point.second)) continue;
      y_min = std::min(y_min, point.second);
      y_max = std::max(y_max, point.second);
    }
  }
  if (!std::isfinite(y_min)) y_min = 0.0, y_max = 1.0;
  if (y_max - y_min < 1e-9) y_min -= 1.0, y_max += 1.0;
  const double step = tick_step(y_max - y_min);
  y_min = std::floor(y_min / step) * step;
  y_max = std::ceil(y_max / step) * step;

  const auto x_of = [&plot](double value) {
    const auto scale = [&plot](double v) { return plot.log_x ? std::log(v) : v; };
    const double lo = scale(plot.x_ticks.front());
    const double hi = scale(plot.x_ticks.back());
    return kLeft + (scale(value) - lo) / (hi - lo) * (kRight - kLeft);
  };
  const auto y_of = [&](double value) {
    return kBottom - (value - y_min) / (y_max - y_min) * (kBottom - kTop);
  };

  std::string svg = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} "
      "{1}\" font-family=\"sans-serif\" font-size=\"12\">\n"
      "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      "<text x=\"{2}\" y=\"22\" font-size=\"15\" text-anchor=\"middle\">{3}</text>\n",
      kWidth, kHeight, (kLeft + kRight) / 2, escaped(plot.title));
  for (double y = y_min; y <= y_max + step / 2; y += step) {
    svg += fmt::format(
        "<line x1=\"{0}\" y1=\"{1:.1f}\" x2=\"{2}\" y2=\"{1:.1f}\" stroke=\"#ddd\"/>"
        "<text x=\"{3}\" y=\"{4:.1f}\" text-anchor=\"end\">{5:g}</text>\n",
        kLeft, y_of(y), kRight, kLeft - 6, y_of(y) + 4, std::round(y / step) * step);
  }
  for (const double x : plot.x_ticks) {
    svg += fmt::format(
        "<line x1=\"{0:.1f}\" y1=\"{1}\" x2=\"{0:.1f}\" y2=\"{2}\" stroke=\"#ddd\"/>"
        "<text x=\"{0:.1f}\" y=\"{3}\" text-anchor=\"middle\">{4:g}</text>\n",
        x_of(x), kTop, kBottom, kBottom + 18, x);
  }
  svg += fmt::format(
      "<rect x=\"{0}\" y=\"{1}\" width=\"{2}\" height=\"{3}\" fill=\"none\" stroke=\"black\"/>\n"
      "<text x=\"{4}\" y=\"{5}\" text-anchor=\"middle\">{6}</text>\n"
      "<text x=\"18\" y=\"{7}\" text-anchor=\"middle\" transform=\"rotate(-90 18 "
      "{7})\">{8}</text>\n",
      kLeft, kTop, kRight - kLeft, kBottom - kTop, (kLeft + kRight) / 2, kBottom + 42,
      escaped(plot.x_label), (kTop + kBottom) / 2, escaped(plot.y_label));

  for (std::size_t i = 0; i < plot.series.size(); ++i) {
    const LineSeries& series = plot.series[i];
    const char* colour = kColours[i % kColours.size()];
    const char* dash = kDashes[(i / kColours.size()) % kDashes.size()];
    const double width = series.emphasised ? 3.0 : 1.5;
    std::string points;
    for (const auto& point : series.points) {
      if (!std::isfinite(point.second)) continue;
      points += fmt::format("{:.1f},{:.1f} ", x_of(point.first), y_of(point.second));
    }
    svg += fmt::format(
        "<polyline fill=\"none\" stroke=\"{}\" stroke-width=\"{}\" stroke-dasharray=\"{}\" "
        "points=\"{}\"/>\n",
        colour, width, dash, points);
    for (const auto& point : series.points) {
      if (!std::isfinite(point.second)) continue;
      svg += fmt::format("<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"{}\" fill=\"{}\"/>\n",
                         x_of(point.first), y_of(point.second), width + 1.0, colour);
    }
    const double legend_y = kTop + 8 + 18.0 * static_cast<double>(i);
    svg += fmt::format(
        "<line x1=\"{0}\" y1=\"{1:.1f}\" x2=\"{2}\" y2=\"{1:.1f}\" stroke=\"{3}\" "
        "stroke-width=\"{4}\" stroke-dasharray=\"{5}\"/>"
        "<text x=\"{6}\" y=\"{7:.1f}\">{8}</text>\n",
        kRight + 20, legend_y, kRight + 50, colour, width, dash, kRight + 56, legend_y + 4,
        escaped(series.name));
  }
  svg += "</svg>\n";
  return svg;
}

}  // namespace rtmot::study
