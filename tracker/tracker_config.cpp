#include "tracker/tracker_config.hpp"

namespace rtmot::tracker {

TrackerConfig with_every_option(TrackerConfig base) {
  base.second_round = true;
  base.detection_threshold = 0.6F;
  base.low_score = 0.3F;
  base.observation_centric_reupdate = true;
  base.time_widened_gate = true;
  base.recent_tracks_first = true;
  base.confirm_by_duration = true;
  base.min_coast_updates = 1;
  base.max_age = 3;
  return base;
}

TrackerConfig TrackerConfig::sort_preset() {
  TrackerConfig config;
  config.predictor = PredictorKind::kalman;
  config.affinity = AffinityKind::iou;
  config.affinity_threshold = default_threshold(AffinityKind::iou);
  config.detection_threshold = 0.0F;
  config.max_age = 1;
  config.min_hits = 3;
  config.time_step = TimeStep::per_update;
  return config;
}

double default_threshold(AffinityKind affinity) {
  switch (affinity) {
    case AffinityKind::iou:
      return 0.3;
    case AffinityKind::linear:
      return 10000.0;
    case AffinityKind::exponential:
      return 0.5;
  }
  return 0.3;
}

std::string_view to_string(PredictorKind kind) {
  switch (kind) {
    case PredictorKind::kalman:
      return "kalman";
    case PredictorKind::stationary:
      return "stationary";
    case PredictorKind::particle:
      return "particle";
  }
  return "unknown";
}

std::string_view to_string(AffinityKind kind) {
  switch (kind) {
    case AffinityKind::iou:
      return "iou";
    case AffinityKind::linear:
      return "linear";
    case AffinityKind::exponential:
      return "exponential";
  }
  return "unknown";
}

std::string_view to_string(TimeStep step) {
  switch (step) {
    case TimeStep::per_update:
      return "per_update";
    case TimeStep::elapsed:
      return "elapsed";
  }
  return "unknown";
}

std::optional<PredictorKind> parse_predictor(std::string_view text) {
  for (auto kind : {PredictorKind::kalman, PredictorKind::stationary, PredictorKind::particle}) {
    if (text == to_string(kind)) return kind;
  }
  return std::nullopt;
}

std::optional<AffinityKind> parse_affinity(std::string_view text) {
  if (text == "exp") return AffinityKind::exponential;  // C++SORT's short name
  for (auto kind : {AffinityKind::iou, AffinityKind::linear, AffinityKind::exponential}) {
    if (text == to_string(kind)) return kind;
  }
  return std::nullopt;
}

std::optional<TimeStep> parse_time_step(std::string_view text) {
  if (text == "per_update" || text == "per-update") return TimeStep::per_update;
  if (text == "elapsed") return TimeStep::elapsed;
  return std::nullopt;
}

}  // namespace rtmot::tracker
