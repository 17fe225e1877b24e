#include "tracker/tracker.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "tracker/association.hpp"
#include "tracker/box_geometry.hpp"
#include "tracker/predictor.hpp"

namespace rtmot::tracker {
namespace {

// One track slot. Slots never move: a live track keeps its slot (and particle storage) for life.
struct Track {
  Predictor predictor;
  // OC-SORT needs the Kalman state as it was right after the last observation.
  KalmanPredictor at_last_observation{Box{0.F, 0.F, 1.F, 1.F}};
  Box last_observation;
  Box predicted;
  std::int32_t id{0};
  std::int32_t hit_streak{0};
  std::int32_t age{0};
  std::int32_t steps_since_update{0};  // sort.py's time_since_update, in calls
  double frames_since_update{0.0};     // the same in nominal frames (equal with per_update)
  double streak_frames{0.0};           // nominal frames covered by the current hit streak
  float score{0.F};
  std::int32_t class_id{0};
  bool matched{false};
};

constexpr int kTypicalSceneSize = 64;
// Timestamps of nominal frames (f / rate) do not subtract to exactly one period in floating
// point; a track one frame late must not die of a rounding error in the last bit.
constexpr double kFrameTolerance = 1e-6;

struct Match {
  int detection;
  int track;  // position in the live order
};

const TrackerConfig& validated(const TrackerConfig& config) {
  if (const auto problem = config_problem(config))
    throw std::invalid_argument("tracker: " + *problem);
  return config;
}

bool usable(const Detection& detection) {
  return is_finite(detection.box) && detection.box.w > 0.F && detection.box.h > 0.F &&
         std::isfinite(detection.score);
}

}  // namespace

struct Tracker::State {
  explicit State(const TrackerConfig& c)
      : config(validated(c)),
        // MOT15 peaks at 16 detections a frame: a 64 x 64 workspace rarely has to grow.
        associator(std::min(c.max_detections, kTypicalSceneSize),
                   std::min(c.max_tracks, kTypicalSceneSize)) {
    const auto tracks = static_cast<std::size_t>(config.max_tracks);
    const auto detections = static_cast<std::size_t>(config.max_detections);
    slots.resize(tracks);
    free_slots.reserve(tracks);
    order.reserve(tracks);
    if (config.predictor == PredictorKind::particle) {
      particles.resize(tracks * 2 * static_cast<std::size_t>(config.particle_count));
    }
    high.reserve(detections);
    low.reserve(detections);
    rest.reserve(detections);
    rest_index.reserve(detections);
    reports.reserve(tracks);
    matches.reserve(std::min(tracks, detections));
    detection_matched.reserve(detections);
    track_matched.reserve(tracks);
    unmatched_tracks.reserve(tracks);
    candidates.reserve(tracks);
    round_matches.reserve(std::min(tracks, detections));
    restart();
  }

  void restart() {
    order.clear();
    free_slots.clear();
    for (int s = config.max_tracks - 1; s >= 0; --s) free_slots.push_back(s);
    next_id = 1;
    frame_count = 0;
    elapsed_frames = 0.0;
    has_previous_time = false;
    reports.clear();
  }

  double step_length(double time_seconds) {
    if (config.time_step == TimeStep::per_update) return 1.0;
    double dt = 1.0;
    if (has_previous_time) dt = (time_seconds - previous_time) * config.frame_rate;
    previous_time = time_seconds;
    has_previous_time = true;
    return std::isfinite(dt) ? std::max(dt, 0.0) : 1.0;
  }

  void split_detections(const std::vector<Detection>& detections) {
    high.clear();
    low.clear();
    for (const Detection& detection : detections) {
      if (!usable(detection)) continue;
      if (detection.score >= config.detection_threshold) {
        if (static_cast<int>(high.size()) < config.max_detections) high.push_back(detection);
      } else if (config.second_round && detection.score >= config.low_score) {
        if (static_cast<int>(low.size()) < config.max_detections) low.push_back(detection);
      }
    }
  }

  void predict_all(double dt) {
    std::size_t kept = 0;
    for (const int slot : order) {
      Track& track = slots[slot];
      track.predicted = advance(track.predictor, dt);
      ++track.age;
      if (track.steps_since_update > 0) {
        track.hit_streak = 0;
        track.streak_frames = 0.0;
      }
      track.streak_frames += dt;
      ++track.steps_since_update;
      track.frames_since_update += dt;
      track.matched = false;
      if (is_finite(track.predicted)) {
        order[kept++] = slot;
      } else {
        release(slot);
      }
    }
    order.resize(kept);
  }

  // Runs one association round of `detections` against the live tracks at `positions`, and
  // appends the matches with live positions.
  void associate_round(const std::vector<Detection>& detections,
                       const std::vector<int>& positions) {
    candidates.clear();
    for (const int position : positions) {
      const Track& track = slots[order[position]];
      candidates.push_back(AssociationCandidate{track.predicted, track.frames_since_update});
    }
    round_matches.clear();
    associator.associate(config, detections, candidates, round_matches);
    for (const AssociationMatch& m : round_matches)
      matches.push_back(Match{m.detection, positions[m.candidate]});
  }

  void apply(const Match& match, const Detection& detection) {
    Track& track = slots[order[match.track]];
    auto* kalman = std::get_if<KalmanPredictor>(&track.predictor);
    if (config.observation_centric_reupdate && kalman != nullptr && track.steps_since_update > 1) {
      // OC-SORT's ORU: replay the lost frames from the last observation along a straight line to
      // the new one, so the velocity is learnt from observations instead of from the coasting.
      KalmanPredictor replay = track.at_last_observation;
      const int steps = track.steps_since_update;
      const double dt = track.frames_since_update / steps;
      for (int i = 1; i <= steps; ++i) {
        replay.predict(dt);
        replay.update(interpolate(track.last_observation, detection.box,
                                  static_cast<float>(i) / static_cast<float>(steps)));
      }
      *kalman = replay;
    } else {
      correct(track.predictor, detection.box);
    }
    if (config.observation_centric_reupdate && kalman != nullptr) {
      track.at_last_observation = *kalman;
    }
    track.last_observation = detection.box;
    track.steps_since_update = 0;
    track.frames_since_update = 0.0;
    ++track.hit_streak;
    track.score = detection.score;
    track.matched = true;
  }

  void start_track(const Detection& detection) {
    if (free_slots.empty()) return;  // at capacity: the detection is ignored
    const int slot = free_slots.back();
    free_slots.pop_back();
    Track& track = slots[slot];
    track.id = next_id++;
    switch (config.predictor) {
      case PredictorKind::kalman:
        track.predictor.emplace<KalmanPredictor>(detection.box);
        if (config.observation_centric_reupdate) {
          track.at_last_observation = std::get<KalmanPredictor>(track.predictor);
        }
        break;
      case PredictorKind::stationary:
        track.predictor.emplace<StationaryPredictor>(detection.box);
        break;
      case PredictorKind::particle: {
        const auto count = static_cast<std::size_t>(config.particle_count);
        Particle* base = particles.data() + static_cast<std::size_t>(slot) * 2 * count;
        track.predictor.emplace<ParticlePredictor>(
            detection.box, ParticleStorage{base, base + count, config.particle_count}, config.seed,
            track.id);
        break;
      }
    }
    track.last_observation = detection.box;
    track.predicted = detection.box;
    track.hit_streak = 0;
    track.streak_frames = 0.0;
    track.age = 0;
    track.steps_since_update = 0;
    track.frames_since_update = 0.0;
    track.score = detection.score;
    track.class_id = detection.class_id;
    track.matched = true;  // sort.py reports a newborn track in the first min_hits frames
    order.push_back(slot);
  }

  void release(int slot) {
    slots[slot].predictor.emplace<std::monostate>();
    free_slots.push_back(slot);
  }

  const std::vector<TrackReport>& update(const std::vector<Detection>& detections,
                                         double time_seconds) {
    ++frame_count;
    const double dt = step_length(time_seconds);
    if (frame_count > 1) elapsed_frames += dt;
    split_detections(detections);
    predict_all(dt);

    matches.clear();
    unmatched_tracks.clear();
    for (int t = 0; t < static_cast<int>(order.size()); ++t) {
      if (!config.recent_tracks_first || slots[order[t]].steps_since_update == 1)
        unmatched_tracks.push_back(t);
    }
    associate_round(high, unmatched_tracks);
    detection_matched.assign(high.size(), 0);
    track_matched.assign(order.size(), 0);
    if (config.recent_tracks_first) associate_older_tracks();
    mark_matches();
    for (const Match& match : matches) apply(match, high[match.detection]);

    if (config.second_round && !low.empty()) {
      // ByteTrack: low-score detections may only continue tracks the first round left unmatched.
      collect_unmatched_tracks();
      matches.clear();
      associate_round(low, unmatched_tracks);
      for (const Match& match : matches) apply(match, low[match.detection]);
    }

    for (std::size_t d = 0; d < high.size(); ++d) {
      if (!detection_matched[d]) start_track(high[d]);
    }

    report_and_retire();
    return reports;
  }

  void mark_matches() {
    for (const Match& match : matches) {
      detection_matched[match.detection] = 1;
      track_matched[match.track] = 1;
    }
  }

  // The tracks (indices into `order`) that no match has claimed yet.
  void collect_unmatched_tracks() {
    unmatched_tracks.clear();
    for (int t = 0; t < static_cast<int>(order.size()); ++t) {
      if (!track_matched[t]) unmatched_tracks.push_back(t);
    }
  }

  bool confirmed(const Track& track) const {
    if (track.hit_streak >= config.min_hits || frame_count <= config.min_hits) return true;
    if (!config.confirm_by_duration) return false;
    // The streak's first frame is the birth (or re-match) itself, hence the one frame less than
    // hits; at full rate this is exactly the hit count.
    return track.hit_streak >= 1 && (track.streak_frames + kFrameTolerance >= config.min_hits ||
                                     elapsed_frames + kFrameTolerance < config.min_hits);
  }

  // DeepSORT's matching cascade in two levels: the tracks lost for a while (whose gate is wide and
  // whose prediction is poor) only get the detections the recently matched tracks left over.
  void associate_older_tracks() {
    mark_matches();
    rest.clear();
    rest_index.clear();
    for (std::size_t d = 0; d < high.size(); ++d) {
      if (detection_matched[d]) continue;
      rest.push_back(high[d]);
      rest_index.push_back(static_cast<int>(d));
    }
    collect_unmatched_tracks();
    const std::size_t first_round = matches.size();
    associate_round(rest, unmatched_tracks);
    for (std::size_t m = first_round; m < matches.size(); ++m) {
      matches[m].detection = rest_index[static_cast<std::size_t>(matches[m].detection)];
    }
  }

  void report_and_retire() {
    reports.clear();
    std::size_t kept = 0;
    for (const int slot : order) {
      const Track& track = slots[slot];
      if (track.matched && confirmed(track)) {
        reports.push_back(TrackReport{track.id, current_box(track.predictor), track.score,
                                      track.class_id, track.hit_streak, track.age});
      }
      if (track.frames_since_update > config.max_age + kFrameTolerance &&
          track.steps_since_update > config.min_coast_updates) {
        release(slot);
      } else {
        order[kept++] = slot;
      }
    }
    order.resize(kept);
  }

  TrackerConfig config;
  std::vector<Track> slots;
  std::vector<int> free_slots;
  std::vector<int> order;  // live slots, oldest first (sort.py's list order)
  std::vector<Particle> particles;
  std::vector<Detection> high;
  std::vector<Detection> low;
  std::vector<Detection> rest;  // the cascade's second level: detections left by the first
  std::vector<int> rest_index;  // their index in `high`
  std::vector<AssociationCandidate> candidates;
  std::vector<AssociationMatch> round_matches;
  std::vector<Match> matches;
  std::vector<char> detection_matched;
  std::vector<char> track_matched;
  std::vector<int> unmatched_tracks;
  std::vector<TrackReport> reports;
  Associator associator;
  std::int32_t next_id{1};
  int frame_count{0};
  double elapsed_frames{0.0};  // nominal frames since the first update
  double previous_time{0.0};
  bool has_previous_time{false};
};

Tracker::Tracker(const TrackerConfig& config) : state_(std::make_unique<State>(config)) {}
Tracker::~Tracker() = default;
Tracker::Tracker(Tracker&&) noexcept = default;
Tracker& Tracker::operator=(Tracker&&) noexcept = default;

const std::vector<TrackReport>& Tracker::update(const std::vector<Detection>& detections,
                                                double time_seconds) {
  return state_->update(detections, time_seconds);
}

void Tracker::reset() {
  state_->restart();
}

const TrackerConfig& Tracker::config() const {
  return state_->config;
}

int Tracker::live_tracks() const {
  return static_cast<int>(state_->order.size());
}

}  // namespace rtmot::tracker
