#include "tracker/affinity.hpp"

#include <algorithm>
#include <cmath>

#include "tracker/box_geometry.hpp"

namespace rtmot::tracker {
namespace {
// A track that was matched in the previous frame keeps the plain gate; each further frame lost
// widens it, up to a bound (max_gate_margin) past which unrelated objects would start to match.
constexpr double kMarginPerLostFrame = 0.15;
}  // namespace

float iou_affinity(const Box& track, const Box& detection) {
  return iou(track, detection);
}

double linear_affinity(const Box& track, const Box& detection, float image_width,
                       float image_height) {
  const double diagonal = std::hypot(double{image_width}, double{image_height});
  const double image_area = double{image_width} * double{image_height};
  const double distance = std::hypot(double{track.center_x()} - detection.center_x(),
                                     double{track.center_y()} - detection.center_y());
  const double area_difference = std::abs(double{track.area()} - double{detection.area()});
  const double cost = (distance / diagonal) * (area_difference / image_area);
  if (!(cost > 1.0 / kMaxLinearAffinity)) return kMaxLinearAffinity;  // also catches NaN
  return 1.0 / cost;
}

double exponential_affinity(const Box& track, const Box& detection) {
  const double dx = (double{track.center_x()} - detection.center_x()) / track.w;
  const double dy = (double{track.center_y()} - detection.center_y()) / track.h;
  const double position = std::exp(-0.5 * (dx * dx + dy * dy));
  const double shape =
      std::exp(-1.5 * (std::abs(double{track.h} - detection.h) / (double{track.h} + detection.h) +
                       std::abs(double{track.w} - detection.w) / (double{track.w} + detection.w)));
  const double result = position * shape;
  return std::isfinite(result) ? result : 0.0;
}

float widened_gate_margin(double gate_frames, double max_margin) {
  return static_cast<float>(std::clamp((gate_frames - 1.0) * kMarginPerLostFrame, 0.0, max_margin));
}

double affinity(const TrackerConfig& config, const Box& track, const Box& detection,
                double gate_frames, float noise_margin) {
  const float time_margin =
      config.time_widened_gate ? widened_gate_margin(gate_frames, config.max_gate_margin) : 0.F;
  const float margin =
      std::min(std::max(time_margin, noise_margin), static_cast<float>(config.max_gate_margin));
  switch (config.affinity) {
    case AffinityKind::iou:
      if (margin > 0.F) return iou(enlarged(track, margin), enlarged(detection, margin));
      return iou(track, detection);
    case AffinityKind::linear:
      return linear_affinity(track, detection, config.image_width, config.image_height) *
             (1.0 + 2.0 * margin);
    case AffinityKind::exponential:
      return exponential_affinity(track, detection) * (1.0 + 2.0 * margin);
  }
  return 0.0;
}

}  // namespace rtmot::tracker
