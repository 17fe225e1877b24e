#include "outputs/events_overlay.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <opencv2/imgproc.hpp>

#include "outputs/overlay.hpp"

namespace rtmot::outputs {
namespace {

const cv::Scalar kLineColour{0, 215, 255};  // amber (BGR): apart from the tracks' colours
const cv::Scalar kZoneColour{255, 160, 0};  // azure
const cv::Scalar kTextBackground{0, 0, 0};

cv::Point pixel(const events::Point& p) {
  return {static_cast<int>(std::lround(p.x)), static_cast<int>(std::lround(p.y))};
}

void label(cv::Mat& image, const std::string& text, cv::Point at, const cv::Scalar& colour,
           const OverlayStyle& style) {
  int baseline = 0;
  const cv::Size size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, style.font_scale,
                                        style.font_thickness, &baseline);
  at.x = std::clamp(at.x, 0, std::max(0, image.cols - size.width - 2 * style.pad));
  at.y = std::clamp(at.y, size.height + 2 * style.pad,
                    std::max(size.height + 2 * style.pad, image.rows));
  cv::rectangle(image, {at.x, at.y - size.height - 2 * style.pad},
                {at.x + size.width + 2 * style.pad, at.y + baseline}, kTextBackground, cv::FILLED);
  cv::putText(image, text, {at.x + style.pad, at.y - style.pad}, cv::FONT_HERSHEY_SIMPLEX,
              style.font_scale, colour, style.font_thickness, cv::LINE_AA);
}

}  // namespace

EventsOverlay::EventsOverlay(events::EventsConfig config)
    : config_(std::move(config)),
      lines_(config_.lines.size()),
      occupancy_(config_.zones.size(), 0) {
  for (const auto& zone : config_.zones) {
    std::vector<cv::Point> polygon;
    for (const auto& p : zone.polygon) polygon.push_back(pixel(p));
    polygons_.push_back(std::move(polygon));
  }
}

void EventsOverlay::count(const messages::FrameResult& result) {
  for (const auto& event : result.events) {
    const std::size_t i = event.index;
    switch (event.kind) {
      case events::EventKind::line_in:
        if (i < lines_.size()) ++lines_[i].in;
        break;
      case events::EventKind::line_out:
        if (i < lines_.size()) ++lines_[i].out;
        break;
      case events::EventKind::zone_enter:
        if (i < occupancy_.size()) ++occupancy_[i];
        break;
      case events::EventKind::zone_exit:
        if (i < occupancy_.size()) occupancy_[i] = std::max<std::int64_t>(0, occupancy_[i] - 1);
        break;
      case events::EventKind::zone_dwell:
        break;
    }
  }
}

void EventsOverlay::draw(cv::Mat& image) {
  const OverlayStyle style = OverlayStyle::for_height(image.rows);
  for (std::size_t z = 0; z < polygons_.size(); ++z) {
    cv::polylines(image, polygons_[z], true, kZoneColour, style.line_thickness, cv::LINE_AA);
    text_.clear();
    fmt::format_to(std::back_inserter(text_), "{}: {} inside", config_.zones[z].name,
                   occupancy_[z]);
    label(image, text_, polygons_[z].front(), kZoneColour, style);
  }
  for (std::size_t l = 0; l < lines_.size(); ++l) {
    const auto& segment = config_.lines[l].segment;
    cv::line(image, pixel(segment.from), pixel(segment.to), kLineColour, style.line_thickness,
             cv::LINE_AA);
    text_.clear();
    fmt::format_to(std::back_inserter(text_), "{}: in {} out {}", config_.lines[l].name,
                   lines_[l].in, lines_[l].out);
    const cv::Point middle = (pixel(segment.from) + pixel(segment.to)) / 2;
    label(image, text_, middle, kLineColour, style);
  }
}

}  // namespace rtmot::outputs
