#include "outputs/overlay.hpp"

#include <fmt/format.h>

#include <algorithm>
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

// Black or white text, whichever reads better on `background`.
cv::Scalar text_colour_on(const cv::Scalar& background) {
  const double luma = 0.114 * background[0] + 0.587 * background[1] + 0.299 * background[2];
  return luma > 140.0 ? cv::Scalar(0, 0, 0) : cv::Scalar(255, 255, 255);
}

// Text on a filled box whose top-left is `box`'s (sized by label_box()).
void put_label(cv::Mat& image, const std::string& text, const cv::Rect& box,
               const cv::Scalar& background, const OverlayStyle& style) {
  cv::rectangle(image, box, background, cv::FILLED);
  cv::putText(image, text, box.tl() + cv::Point(style.pad, box.height - style.pad - style.baseline),
              font, style.font_scale, text_colour_on(background), style.font_thickness,
              cv::LINE_AA);
}

void dashed_rectangle(cv::Mat& image, const cv::Rect& box, const cv::Scalar& colour,
                      int thickness) {
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
      cv::line(image, at(start), at(end), colour, thickness);
    }
  }
}

}  // namespace

// Where a label goes: above its box if free, else just inside its top, else below it, else moved
// down (then up) in steps of its height until it overlaps no label placed before it. Close people
// hid each other's labels (frames 51, 302, 701 of vtest.avi: only a neighbour's "0.83" showed).
cv::Rect place_label(const cv::Size& size, const cv::Rect& box, const cv::Size& image,
                     const std::vector<cv::Rect>& placed) {
  const auto inside = [&](cv::Point corner) {
    corner.x = std::clamp(corner.x, 0, std::max(0, image.width - size.width));
    corner.y = std::clamp(corner.y, 0, std::max(0, image.height - size.height));
    return cv::Rect(corner, size);
  };
  const auto free = [&](const cv::Rect& rect) {
    return std::none_of(placed.begin(), placed.end(),
                        [&](const cv::Rect& other) { return (rect & other).area() > 0; });
  };
  const std::array<cv::Point, 3> preferred = {
      cv::Point(box.x, box.y - size.height), cv::Point(box.x, box.y), cv::Point(box.x, box.br().y)};
  for (const cv::Point& corner : preferred) {
    const cv::Rect rect = inside(corner);
    if (free(rect)) return rect;
  }
  const cv::Rect start = inside(preferred[0]);
  for (int step = 1; step < 64; ++step) {
    for (const int sign : {1, -1}) {
      const cv::Rect rect = inside(start.tl() + cv::Point(0, sign * step * size.height));
      if (free(rect)) return rect;
    }
  }
  return start;  // a crowd too dense for any free place: on top, as before
}

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

OverlayStyle OverlayStyle::for_height(int rows) {
  // Tuned at 576 rows (vtest.avi): 0.5 scale, 1 px text, 2 px boxes; proportional elsewhere, so a
  // 1080p frame's labels are as readable as a 576p one's and a 240p one's do not cover it.
  OverlayStyle style;
  const double factor = std::max(rows, 1) / 576.0;
  style.font_scale = std::clamp(0.5 * factor, 0.35, 2.0);
  style.font_thickness = std::max(1, static_cast<int>(std::lround(factor)));
  style.line_thickness = std::max(2, static_cast<int>(std::lround(2.0 * factor)));
  style.pad = std::max(2, static_cast<int>(std::lround(2.0 * factor)));
  int baseline = 0;
  const cv::Size size =
      cv::getTextSize("#0", font, style.font_scale, style.font_thickness, &baseline);
  style.baseline = baseline;
  style.text_height = size.height;
  return style;
}

cv::Scalar class_colour(std::int32_t class_id) {
  // DeepStream's convention: the box's colour says the class. Fixed for the classes seen most
  // (COCO 1 person: green, 3 car: blue, 2 bicycle: orange, 4 motorcycle: magenta), stable hues
  // for the others.
  switch (class_id) {
    case 1:
      return {60, 200, 60};
    case 2:
      return {0, 140, 255};
    case 3:
      return {255, 120, 0};
    case 4:
      return {200, 0, 200};
    default:
      return colour_of(class_id + 1000);
  }
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
  placed_.reserve(max_tracks + 1);
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
  if (image.rows != style_rows_) {
    style_ = OverlayStyle::for_height(image.rows);
    style_rows_ = image.rows;
  }
  // Boxes and trails first, every label after them: no box is drawn over a label.
  for (const auto& track : result.tracks) {
    const cv::Scalar colour = class_colour(track.class_id);
    const cv::Rect box = box_of(track);
    if (flags_.has(OverlayFlag::trail)) {
      if (Trail* trail = trail_of(track.id, result.frame_number)) {
        if (!predicted) {
          trail->points[trail->next] = cv::Point(box.x + box.width / 2, box.br().y);
          trail->next = (trail->next + 1) % trail->points.size();
          trail->size = std::min(trail->size + 1, trail->points.size());
          trail->last_frame = result.frame_number;
        }
        // The trail in the track's own colour: two people of one class stay apart.
        const cv::Scalar trail_colour = colour_of(track.id);
        for (std::size_t i = 1; i < trail->size; ++i) {
          const std::size_t n = trail->points.size();
          const cv::Point& a = trail->points[(trail->next + n - i - 1) % n];
          const cv::Point& b = trail->points[(trail->next + n - i) % n];
          cv::line(image, a, b, trail_colour, style_.line_thickness, cv::LINE_AA);
        }
      }
    }
    if (flags_.has(OverlayFlag::box)) {
      if (predicted) {
        dashed_rectangle(image, box, colour, std::max(1, style_.line_thickness / 2));
      } else {
        cv::rectangle(image, box, colour, style_.line_thickness);
      }
    }
  }
  placed_.clear();
  if (flags_.has(OverlayFlag::stats)) {
    text_.clear();
    fmt::format_to(std::back_inserter(text_),
                   "frame {}  {:.1f} fps  latency {:.0f} ms  {} tracks{}", result.frame_number,
                   stats.fps, stats.latency_ms, result.tracks.size(),
                   predicted ? "  (predicted)" : "");
    const cv::Rect at(cv::Point(4, 4), label_size(text_));
    put_label(image, text_, at, cv::Scalar(32, 32, 32), style_);
    placed_.push_back(at);
  }
  for (const auto& track : result.tracks) {
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
    if (text_.empty()) continue;
    const cv::Rect at = place_label(label_size(text_), box_of(track), image.size(), placed_);
    put_label(image, text_, at, class_colour(track.class_id), style_);
    placed_.push_back(at);
  }
}

cv::Size Overlay::label_size(const std::string& text) const {
  int baseline = 0;
  const cv::Size size =
      cv::getTextSize(text, font, style_.font_scale, style_.font_thickness, &baseline);
  return {size.width + 2 * style_.pad, size.height + baseline + 2 * style_.pad};
}

cv::Rect Overlay::box_of(const tracker::TrackReport& track) {
  return {cv::Point(static_cast<int>(track.box.x), static_cast<int>(track.box.y)),
          cv::Size(static_cast<int>(track.box.w), static_cast<int>(track.box.h))};
}

}  // namespace rtmot::outputs
