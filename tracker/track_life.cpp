// Tracker::State's track life (tracker_state.hpp): tracks are predicted, corrected by what matched
// or what the image showed, started from leftover detections, settled, reported and released.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <variant>
#include <vector>

#include "tracker/appearance.hpp"
#include "tracker/box_geometry.hpp"
#include "tracker/crossings.hpp"
#include "tracker/predictor.hpp"
#include "tracker/tracker_extension.hpp"
#include "tracker/tracker_state.hpp"

namespace rtmot::tracker {
namespace {

// The box noise is measured on matches about one nominal frame ahead: a live camera's timestamps
// jitter, and two frames ahead the offset is mostly motion (the time-widened gate's business).
constexpr double kOneFrameSlack = 0.5;

}  // namespace

// Every live track advances by `dt` nominal frames and starts the update coasting; a track
// whose prediction is no longer finite is deleted.
void Tracker::State::predict_tracks(double dt) {
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
    track.model_started_now = false;
    track.observed_now = false;
    ++track.steps_since_update;
    track.frames_since_update += dt;
    if (is_finite(track.predicted)) {
      order[kept++] = slot;
    } else {
      release(slot);
    }
  }
  order.resize(kept);
}

// Each observed track's prior moves to what the image showed, before any association sees it.
// A linear search per box: a frame holds tens of tracks, and this allocates nothing.
void Tracker::State::correct_with_observed(const std::vector<ObservedBox>& observed) {
  for (const ObservedBox& seen : observed) {
    if (!is_finite(seen.box) || seen.box.w <= 0.F || seen.box.h <= 0.F) continue;
    for (const int slot : order) {
      Track& track = slots[slot];
      if (track.id != seen.id) continue;
      correct(track.predictor, seen.box);
      const Box corrected = current_box(track.predictor);
      if (is_finite(corrected)) track.predicted = corrected;
      track.observed_now = true;
      break;
    }
  }
}

void Tracker::State::correct_track(Track& track, const Detection& detection) {
  // The box noise is measured on matches one nominal frame ahead only: further ahead the
  // offset is mostly the motion the time-widened gate answers for.
  if (track.steps_since_update == 1 && std::abs(step_frames - 1.0) <= kOneFrameSlack)
    box_noise.observe(track.predicted, detection.box);
  auto* kalman = std::get_if<KalmanPredictor>(&track.predictor);
  if (config.observation_centric_reupdate && kalman != nullptr && track.steps_since_update > 1) {
    reupdate_from_observations(track, *kalman, detection.box);
  } else {
    correct(track.predictor, detection.box);
  }
  if (config.observation_centric_reupdate && kalman != nullptr) {
    track.at_last_observation = *kalman;
  }
  track.last_observation = detection.box;
  track.model_started_now = !track.appearance.valid && detection.appearance.valid;
  if (detection.appearance.valid && track.appearance.valid && track.crossing_partner != 0) {
    track.held_sighting = detection.appearance;  // resolve_crossings() decides whose it is
  } else if (detection.appearance.valid) {       // valid: no other detection covers it
    blend_appearance(track.appearance, detection.appearance,
                     static_cast<float>(config.appearance_momentum));
  }
  track.steps_since_update = 0;
  track.frames_since_update = 0.0;
  track.last_seen_seconds = last_update_time;
  ++track.hit_streak;
  track.score = detection.score;
  track.score_sum += detection.score;
  ++track.matches;
}

// OC-SORT's ORU: replay the lost frames from the last observation along a straight line to the
// new one, so the velocity is learnt from observations instead of from the coasting.
void Tracker::State::reupdate_from_observations(Track& track, KalmanPredictor& kalman,
                                                const Box& found) {
  KalmanPredictor replay = track.at_last_observation;
  const int steps = track.steps_since_update;
  const double dt = track.frames_since_update / steps;
  for (int i = 1; i <= steps; ++i) {
    replay.predict(dt);
    replay.update(interpolate(track.last_observation, found,
                              static_cast<float>(i) / static_cast<float>(steps)));
  }
  kalman = replay;
}

// Every high-score detection that no round took starts a tentative track (with a birth cut,
// only the confident ones: a continuation needs less evidence than a new object).
void Tracker::State::start_tracks() {
  const float birth = extension ? std::max(config.birth_threshold, extension->birth_cut(score_cut))
                                : config.birth_threshold;
  for (std::size_t d = 0; d < high.size(); ++d) {
    if (!high_taken[d] && high[d].score >= birth) start_track(high[d]);
  }
}

void Tracker::State::start_track(const Detection& detection) {
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
    case PredictorKind::kalman_xyah:
      track.predictor.emplace<XyahKalmanPredictor>(detection.box);
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
  track.score_sum = detection.score;
  track.matches = 1;
  track.class_id = detection.class_id;
  track.appearance = detection.appearance;
  track.last_seen_seconds = last_update_time;
  track.born_seconds = last_update_time;
  track.model_started_now = false;
  track.first_confirmed_now = false;
  track.taken_over = false;
  track.crossing_partner = 0;
  track.held_sighting.valid = false;
  track.life.born();
  track.strong_birth = config.strong_birth_range_cut > 0.0 &&
                       detection.score >= score_cut.range_point(config.strong_birth_range_cut);
  // sort.py reports a newborn track in the first min_hits frames: it counts as matched now
  // (steps_since_update 0).
  order.push_back(slot);
}

// Every track's life moves on: a matched track is confirmed by its run of matches (or, in the
// first frames, by sort.py's warm-up) or not, a missed one is not; confirmed tracks are
// reported; tracks that miss too long (or, with tentative_dies_on_miss, once before they were
// ever confirmed) are removed.
void Tracker::State::settle_and_report() {
  reports.clear();
  for (const int slot : order) {
    Track& track = slots[slot];
    const bool was_confirmed = track.life.ever_confirmed();
    track.life.settle(track.matched_now() && confirmed(track));
    track.first_confirmed_now = !was_confirmed && track.life.stage() == TrackStage::confirmed;
  }
  // resolve_crossings is only on with re-identification (config_problem: reid_gate is on).
  if (config.resolve_crossings) resolve_crossings(table_view());
  if (reidentifier.on()) reidentifier.reidentify_newly_confirmed(table_view());
  std::size_t kept = 0;
  for (const int slot : order) {
    Track& track = slots[slot];
    if (track.taken_over) {
      release(slot);
      continue;
    }
    if (track.life.stage() == TrackStage::confirmed) reports.push_back(report(track));
    const bool unproven_and_missed = config.tentative_dies_on_miss && !track.matched_now() &&
                                     track.life.stage() == TrackStage::tentative;
    if (unproven_and_missed || (track.frames_since_update > config.max_age + kFrameTolerance &&
                                track.steps_since_update > config.min_coast_updates)) {
      reidentifier.remember_departure(track);
      release(slot);
    } else {
      order[kept++] = slot;
    }
  }
  order.resize(kept);
  if (config.resolve_crossings) note_crossings(table_view());
}

TrackReport Tracker::State::report(const Track& track) {
  return TrackReport{track.id,          current_box(track.predictor),
                     track.score,       track.class_id,
                     track.hit_streak,  track.age,
                     track.life.stage()};
}

bool Tracker::State::confirmed(const Track& track) const {
  const TrackFacts facts = track.facts();
  if (!extension) {
    return confirmation.confirms(facts, StreamClock{frame_count, elapsed_frames}, true);
  }
  if (!extension->may_confirm(facts, score_cut)) return false;
  return confirmation.confirms(facts, StreamClock{frame_count, elapsed_frames},
                               extension->may_confirm_by_duration(facts));
}

void Tracker::State::release(int slot) {
  slots[slot].predictor.emplace<std::monostate>();
  slots[slot].life.remove();
  free_slots.push_back(slot);
}

}  // namespace rtmot::tracker
