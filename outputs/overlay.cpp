#include "outputs/overlay.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <string_view>

#include "tracker/enum_names.hpp"

namespace rtmot::outputs {
namespace {

constexpr auto flag_names = tracker::make_enum_names<OverlayFlag>(
    std::pair{OverlayFlag::box, std::string_view("box")},
    std::pair{OverlayFlag::labels, std::string_view("labels")},
    std::pair{OverlayFlag::conf, std::string_view("conf")},
    std::pair{OverlayFlag::track, std::string_view("track")},
    std::pair{OverlayFlag::trail, std::string_view("trail")},
    std::pair{OverlayFlag::stats, std::string_view("stats")});

constexpr int font = cv::FONT_HERSHEY_SIMPLEX;
constexpr double font_scale = 0.5;
constexpr int font_thickness = 1;

// Black or white text, whichever reads better on `background`.
cv::Scalar text_colour_on(const cv::Scalar& background) {
  const double luma = 0.114 * background[0] + 0.587 * background[1] + 0.299 * background[2];
  return luma > 140.0 ? cv::Scalar(0, 0, 0) : cv::Scalar(255, 255, 255);
}

// Text on a filled box, its top-left at `corner`, kept inside the image.
void put_label(cv::Mat& image, const std::string& text, cv::Point corner,
               const cv::Scalar& background) {
  int baseline = 0;
  const cv::Size size = cv::getTextSize(text, font, font_scale, font_thickness, &baseline);
  corner.x = std::clamp(corner.x, 0, std::max(0, image.cols - size.width - 4));
  corner.y = std::clamp(corner.y, 0, std::max(0, image.rows - size.height - baseline - 4));
  const cv::Rect box(corner, cv::Size(size.width + 4, size.height + baseline + 4));
  cv::rectangle(image, box, background, cv::FILLED);
  cv::putText(image, text, corner + cv::Point(2, size.height + 2), font, font_scale,
              text_colour_on(background), font_thickness, cv::LINE_AA);
}

void dashed_rectangle(cv::Mat& image, const cv::Rect& box, const cv::Scalar& colour) {
  constexpr int dash = 6;
  const std::array<std::pair<cv::Point, cv::Point>, 4> sides = {{
      {box.tl(), {box.br().x, box.y}},
      {{box.br().x, box.y}, box.br()},
      {box.br(), {box.x, box.br().y}},
      {{box.x, box.br().y}, box.tl()},
  }};
  for (const auto& side : sides) {
    // Named copies: a C++17 lambda cannot capture structured bindings (clang refuses).
    const cv::Point from = side.first;
    const cv::Point to = side.second;
    const double length = std::hypot(to.x - from.x, to.y - from.y);
    for (double start = 0.0; start < length; start += 2 * dash) {
      const double end = std::min(start + dash, length);
      const auto at = [&](double t) {
        return cv::Point(from.x + static_cast<int>((to.x - from.x) * t / length),
                         from.y + static_cast<int>((to.y - from.y) * t / length));
      };
      cv::line(image, at(start), at(end), colour, 1);
    }
  }
}

}  // namespace

std::optional<OverlayFlags> parse_overlay_flags(const std::string& text, std::string& problem) {
  OverlayFlags flags;
  if (text == "none") return flags;
  std::string_view rest(text);
  while (true) {
    const auto comma = rest.find(',');
    const std::string_view name = rest.substr(0, comma);
    const auto flag = flag_names.parse(name);
    if (!flag) {
      problem = "unknown overlay flag '" + std::string(name) + "' (" + overlay_flag_names() +
                ", or none)";
      return std::nullopt;
    }
    flags.bits |= static_cast<unsigned>(*flag);
    if (comma == std::string_view::npos) break;
    rest = rest.substr(comma + 1);
  }
  return flags;
}

std::string overlay_flag_names() {
  return flag_names.alternatives();
}

cv::Scalar colour_of(std::int32_t id) {
  const double hue = std::fmod(static_cast<double>(id) * 0.618033988749895, 1.0);
  cv::Mat3b hsv(1, 1, cv::Vec3b(static_cast<unsigned char>(hue * 179.0), 220, 255));
  cv::Mat3b bgr;
  cv::cvtColor(hsv, bgr, cv::COLOR_HSV2BGR);
  const cv::Vec3b pixel = bgr(0, 0);
  return {static_cast<double>(pixel[0]), static_cast<double>(pixel[1]),
          static_cast<double>(pixel[2])};
}

Overlay::Overlay(OverlayFlags flags, messages::ClassLabelFn labels, std::size_t max_tracks,
                 std::size_t trail_length)
    : flags_(flags), labels_(labels), trails_(max_tracks) {
  for (Trail& trail : trails_) trail.points.resize(trail_length);
  text_.reserve(64);
}

Overlay::Trail* Overlay::trail_of(std::int32_t id, std::int64_t frame) {
  Trail* oldest = nullptr;
  for (Trail& trail : trails_) {
    if (trail.id == id) return &trail;
    if (oldest == nullptr || trail.last_frame < oldest->last_frame) oldest = &trail;
  }
  if (oldest == nullptr) return nullptr;
  // A new id takes the slot of the track seen longest ago (a gone track's trail).
  oldest->id = id;
  oldest->last_frame = frame;
  oldest->next = 0;
  oldest->size = 0;
  return oldest;
}

void Overlay::draw(cv::Mat& image, const messages::FrameResult& result, bool predicted,
                   const OverlayStats& stats) {
  if (image.empty()) return;
  for (const auto& track : result.tracks) {
    const cv::Scalar colour = colour_of(track.id);
    const cv::Rect box(cv::Point(static_cast<int>(track.box.x), static_cast<int>(track.box.y)),
                       cv::Size(static_cast<int>(track.box.w), static_cast<int>(track.box.h)));
    if (flags_.has(OverlayFlag::trail)) {
      if (Trail* trail = trail_of(track.id, result.frame_number)) {
        if (!predicted) {
          trail->points[trail->next] = cv::Point(box.x + box.width / 2, box.br().y);
          trail->next = (trail->next + 1) % trail->points.size();
          trail->size = std::min(trail->size + 1, trail->points.size());
          trail->last_frame = result.frame_number;
        }
        for (std::size_t i = 1; i < trail->size; ++i) {
          const std::size_t n = trail->points.size();
          const cv::Point& a = trail->points[(trail->next + n - i - 1) % n];
          const cv::Point& b = trail->points[(trail->next + n - i) % n];
          cv::line(image, a, b, colour, 2, cv::LINE_AA);
        }
      }
    }
    if (flags_.has(OverlayFlag::box)) {
      if (predicted) {
        dashed_rectangle(image, box, colour);
      } else {
        cv::rectangle(image, box, colour, 2);
      }
    }
    text_.clear();
    if (flags_.has(OverlayFlag::track)) fmt::format_to(std::back_inserter(text_), "#{}", track.id);
    if (flags_.has(OverlayFlag::labels) && labels_ != nullptr) {
      const std::string_view label = labels_(track.class_id);
      if (!label.empty())
        fmt::format_to(std::back_inserter(text_), "{}{}", text_.empty() ? "" : " ", label);
    }
    if (flags_.has(OverlayFlag::conf) && !predicted && std::isfinite(track.score)) {
      fmt::format_to(std::back_inserter(text_), "{}{:.2f}", text_.empty() ? "" : " ", track.score);
    }
    if (predicted && !text_.empty()) text_ += " ~";  // a prediction, not a detection
    if (!text_.empty()) put_label(image, text_, cv::Point(box.x, box.y - 20), colour);
  }
  if (flags_.has(OverlayFlag::stats)) {
    text_.clear();
    fmt::format_to(std::back_inserter(text_),
                   "frame {}  {:.1f} fps  latency {:.0f} ms  {} tracks{}", result.frame_number,
                   stats.fps, stats.latency_ms, result.tracks.size(),
                   predicted ? "  (predicted)" : "");
    put_label(image, text_, cv::Point(4, 4), cv::Scalar(32, 32, 32));
  }
}

}  // namespace rtmot::outputs
