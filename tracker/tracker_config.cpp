#include "tracker/tracker_config.hpp"

#include <cmath>
#include <limits>

#include "tracker/tracker_limits.hpp"

namespace rtmot::tracker {

TrackerConfig with_every_option(TrackerConfig base) {
  base.second_round = true;
  base.detection_threshold = 0.6F;
  base.low_score = 0.3F;
  base.score_range_cut = 0.5;
  base.score_range_cap = 0.5;
  base.score_range_cap_below = 0.2;
  base.observation_centric_reupdate = true;
  base.time_widened_gate = true;
  base.gate_clock = GateClock::frame_gap;
  base.confirmed_tracks_first = true;
  base.confirm_by_duration = true;
  base.min_coast_updates = 1;
  base.max_age = 3;
  base.duration_min_hits = 2;
  base.keep_confirmation = true;
  base.tentative_dies_on_miss = true;
  base.second_round_recent_only = true;
  base.strong_birth_range_cut = 0.7;
  base.birth_threshold = 0.65F;
  base.second_round_threshold = 0.5;
  base.max_gate_margin = 0.4;
  base.noise_gate_factor = 3.0;
  base.distance_gate_per_frame = 0.5;
  base.distance_gate_max = 5.0;
  base.appearance_gate = 0.8;
  base.appearance_gate_contested = true;
  base.appearance_gate_rival_alike = true;
  base.appearance_weight = 0.5;
  base.reid_gate = 0.3;
  base.handback_gate = 0.5;
  return base;
}

TrackerConfig TrackerConfig::sort_preset() {
  TrackerConfig config;
  config.predictor = PredictorKind::kalman;
  config.affinity = AffinityKind::iou;
  config.affinity_threshold = default_threshold(AffinityKind::iou);
  config.detection_threshold = std::numeric_limits<float>::lowest();  // sort.py keeps every row
  config.score_range_cut = 0.0;
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

std::optional<std::string> config_problem(const TrackerConfig& config) {
  const auto within = [](auto value, auto low, auto high) { return value >= low && value <= high; };
  if (!within(config.max_tracks, 1, limits::kMaxCapacity) ||
      !within(config.max_detections, 1, limits::kMaxCapacity))
    return "max_tracks and max_detections must be in [1, " + std::to_string(limits::kMaxCapacity) +
           "]";
  if (config.predictor == PredictorKind::particle) {
    if (!within(config.particle_count, 1, limits::kMaxParticles))
      return "particle_count must be in [1, " + std::to_string(limits::kMaxParticles) + "]";
    // Every slot owns two buffers of particles, allocated up front.
    if (static_cast<long long>(config.max_tracks) * config.particle_count >
        limits::kMaxParticleStorage)
      return "max_tracks x particle_count must be at most " +
             std::to_string(limits::kMaxParticleStorage) +
             " (the particles are allocated up front)";
  }
  if (!within(config.max_age, 0, limits::kMaxFrames) ||
      !within(config.min_hits, 0, limits::kMaxFrames) ||
      !within(config.min_coast_updates, 0, limits::kMaxFrames))
    return "max_age, min_hits and min_coast_updates must be in [0, " +
           std::to_string(limits::kMaxFrames) + "]";
  if (config.time_step == TimeStep::elapsed && !(config.frame_rate > 0.0))
    return "frame_rate must be > 0 with elapsed time steps";
  if (!std::isfinite(config.affinity_threshold)) return "affinity_threshold must be finite";
  if (std::isnan(config.detection_threshold) || std::isnan(config.low_score) ||
      std::isnan(config.birth_threshold))
    return "detection_threshold, low_score and birth_threshold must be numbers";
  if (!(config.score_range_cut >= 0.0 && config.score_range_cut <= limits::kMaxScoreQuantile))
    return "score_range_cut must be in [0, " + std::to_string(limits::kMaxScoreQuantile) + "]";
  if (!(config.strong_birth_range_cut >= 0.0 &&
        config.strong_birth_range_cut <= limits::kMaxScoreQuantile))
    return "strong_birth_range_cut must be in [0, " + std::to_string(limits::kMaxScoreQuantile) +
           "]";
  if (!(config.noise_gate_factor >= 0.0 && config.noise_gate_factor <= limits::kMaxNoiseGateFactor))
    return "noise_gate_factor must be in [0, " + std::to_string(limits::kMaxNoiseGateFactor) + "]";
  if (!(config.distance_gate_per_frame >= 0.0 &&
        config.distance_gate_per_frame <= limits::kMaxDistanceGate &&
        config.distance_gate_max >= 0.0 && config.distance_gate_max <= limits::kMaxDistanceGate))
    return "distance_gate_per_frame and distance_gate_max must be in [0, " +
           std::to_string(limits::kMaxDistanceGate) + "]";
  if (!(config.appearance_gate >= 0.0 && config.appearance_gate <= 1.0 &&
        config.appearance_weight >= 0.0 && config.appearance_weight <= 1.0))
    return "appearance_gate and appearance_weight must be in [0, 1]";
  if (!(config.appearance_momentum >= 0.0 && config.appearance_momentum < 1.0))
    return "appearance_momentum must be in [0, 1)";
  if (config.appearance_gate_rival_alike && !config.appearance_gate_contested)
    return "appearance_gate_rival_alike needs appearance_gate_contested: it narrows which "
           "contested pairs the gate refuses";
  if (!(config.observed_gate_frames >= 0.0 && config.observed_gate_frames <= limits::kMaxFrames))
    return "observed_gate_frames must be in [0, " + std::to_string(limits::kMaxFrames) + "]";
  if (config.handback_gate > 0.0 && !(config.reid_gate > 0.0))
    return "handback_gate needs re-identification on (reid_gate above 0): a box goes back to "
           "a track that re-identification would judge its person's";
  if (config.resolve_crossings && !(config.reid_gate > 0.0))
    return "resolve_crossings needs re-identification on (reid_gate above 0): its trades are "
           "bounded by reid_gate";
  return std::nullopt;
}

}  // namespace rtmot::tracker
