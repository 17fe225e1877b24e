#include "tracker/tracker.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "tracker/appearance.hpp"
#include "tracker/association.hpp"
#include "tracker/box_geometry.hpp"
#include "tracker/box_noise.hpp"
#include "tracker/crossings.hpp"
#include "tracker/handback.hpp"
#include "tracker/predictor.hpp"
#include "tracker/reidentification.hpp"
#include "tracker/score_cut.hpp"
#include "tracker/track.hpp"
#include "tracker/track_table.hpp"
#include "tracker/tracker_extension.hpp"

namespace rtmot::tracker {
namespace {

constexpr int kTypicalSceneSize = 64;
// The box noise is measured on matches about one nominal frame ahead: a live camera's timestamps
// jitter, and two frames ahead the offset is mostly motion (the time-widened gate's business).
constexpr double kOneFrameSlack = 0.5;
// A detection whose box another detection covers this much of shows someone else's pixels too:
// its appearance does not teach its track (a tenth of a person is an arm or a bag).
constexpr float kOccludedShare = 0.1F;

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

// The update is a sequence of named passes over a table of track slots (see update()). Every
// buffer below is sized at construction; a pass only clears and refills them. The identity passes
// that decide on the looks alone (the hand-back's choice of owner, crossing resolution,
// re-identification) live in their own files and see the table through a TrackTableView.
struct Tracker::State {
  State(const TrackerConfig& c, std::unique_ptr<TrackerExtension> e)
      : config(validated(c)),
        extension(std::move(e)),
        confirmation(ConfirmationPolicy::from(c)),
        // MOT15 peaks at 16 detections a frame: a 64 x 64 workspace rarely has to grow.
        associator(std::min(c.max_detections, kTypicalSceneSize),
                   std::min(c.max_tracks, kTypicalSceneSize)),
        box_noise(c.noise_gate_factor > 0.0 ? kBoxNoiseWindow : 0),
        score_cut(0.0, c.score_range_cut, kScoreWindow,
                  c.strong_birth_range_cut > 0.0 || (extension && extension->needs_score_range()),
                  c.score_range_cap, c.score_range_cap_below),
        cascades(c.confirmed_tracks_first || (extension && extension->cascades())),
        reidentifier(config.reid_gate > 0.0 ? static_cast<std::size_t>(config.max_tracks) : 0) {
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
    high_taken.reserve(detections);
    hidden_flags.resize(2 * detections);  // high and low together: at most max_detections each
    positions.reserve(tracks);
    candidates.reserve(tracks);
    round_matches.reserve(std::min(tracks, detections));
    handovers.reserve(std::min(tracks, detections));
    reports.reserve(tracks);
    table.reserve(tracks);
    restart();
  }

  void restart() {
    for (const int slot : order) slots[slot].life.remove();
    order.clear();
    free_slots.clear();
    for (int s = config.max_tracks - 1; s >= 0; --s) free_slots.push_back(s);
    next_id = 1;
    frame_count = 0;
    elapsed_frames = 0.0;
    has_previous_time = false;
    last_update_time = 0.0;
    last_gap_seconds = 0.0;
    score_cut.reset();
    box_noise.reset();
    if (extension) extension->reset();
    reports.clear();
    reidentifier.reset();
  }

  // One frame: predict, associate in up to three rounds, start tracks, settle states and report.
  const std::vector<TrackReport>& update(const std::vector<Detection>& detections,
                                         double time_seconds,
                                         const std::vector<ObservedBox>* observed) {
    ++frame_count;
    if (frame_count > 1) last_gap_seconds = time_seconds - last_update_time;
    last_update_time = time_seconds;
    const double dt = step_length(time_seconds);
    step_frames = dt;
    if (frame_count > 1) elapsed_frames += dt;
    split_by_score(detections);
    predict_tracks(dt);
    if (observed != nullptr) correct_with_observed(*observed);
    first_round();
    if (cascades) cascade_round();
    if (config.second_round && !low.empty()) second_round();
    if (config.distance_gate_per_frame > 0.0) distance_round();
    start_tracks();
    settle_and_report();
    return reports;
  }

  double step_length(double time_seconds) {
    if (config.time_step == TimeStep::per_update) return 1.0;
    double dt = 1.0;
    if (has_previous_time) dt = (time_seconds - previous_time) * config.frame_rate;
    previous_time = time_seconds;
    has_previous_time = true;
    return std::isfinite(dt) ? std::max(dt, 0.0) : 1.0;
  }

  // High-score detections may start and continue tracks; low ones (ByteTrack) only continue them.
  // High means at or above both the absolute and the relative cut.
  void split_by_score(const std::vector<Detection>& detections) {
    high.clear();
    low.clear();
    float cut = std::max(config.detection_threshold, score_cut.observe(detections));
    if (extension) cut = std::max(cut, extension->split_cut(detections));
    for (const Detection& detection : detections) {
      if (!usable(detection)) continue;
      if (detection.score >= cut) {
        if (static_cast<int>(high.size()) < config.max_detections) high.push_back(detection);
      } else if (config.second_round && detection.score >= config.low_score) {
        if (static_cast<int>(low.size()) < config.max_detections) low.push_back(detection);
      }
    }
    high_taken.assign(high.size(), 0);
    forget_hidden_appearances();
  }

  // A detection that another one partly covers shows some of the other person's colours: its
  // appearance neither decides a pair nor teaches a track (kOccludedShare).
  void forget_hidden_appearances() {
    std::size_t hidden = 0;
    for (const Detection& d : high) hidden_flags[hidden++] = d.appearance.valid && overlapped(d);
    for (const Detection& d : low) hidden_flags[hidden++] = d.appearance.valid && overlapped(d);
    hidden = 0;
    for (Detection& d : high) d.appearance.valid = d.appearance.valid && !hidden_flags[hidden++];
    for (Detection& d : low) d.appearance.valid = d.appearance.valid && !hidden_flags[hidden++];
  }

  // Every live track advances by `dt` nominal frames and starts the update coasting; a track
  // whose prediction is no longer finite is deleted.
  void predict_tracks(double dt) {
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
  void correct_with_observed(const std::vector<ObservedBox>& observed) {
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

  // SORT's association: the high-score detections against every live track (with the cascade,
  // against the tracks matched in the previous update only; with confirmed_tracks_first, against
  // the confirmed ones only).
  void first_round() {
    positions.clear();
    for (int t = 0; t < static_cast<int>(order.size()); ++t) {
      const Track& track = slots[order[t]];
      if (config.confirmed_tracks_first && !track.life.ever_confirmed()) continue;
      if (extension && extension->defers(track.facts())) continue;
      positions.push_back(t);
    }
    associate(high, [&](int d) { high_taken[static_cast<std::size_t>(d)] = 1; });
  }

  // DeepSORT's matching cascade in two levels: the tracks lost for a while (whose gate is wide and
  // whose prediction is poor), and with confirmed_tracks_first the tracks not yet confirmed, only
  // get the detections the first round left over.
  void cascade_round() {
    collect_leftover_detections();
    collect_coasting_tracks();
    associate(rest, [&](int r) {
      high_taken[static_cast<std::size_t>(rest_index[static_cast<std::size_t>(r)])] = 1;
    });
  }

  // ByteTrack: low-score detections may only continue the tracks the rounds before left coasting
  // (with second_round_recent_only, those of them that were confirmed and matched last update).
  void second_round() {
    collect_coasting_tracks();
    if (config.second_round_recent_only) {
      const auto lost = [&](int position) {
        const Track& track = slots[order[position]];
        return !track.life.ever_confirmed() || track.steps_since_update > 1;
      };
      positions.erase(std::remove_if(positions.begin(), positions.end(), lost), positions.end());
    }
    const double threshold = config.second_round_threshold > 0.0 ? config.second_round_threshold
                                                                 : config.affinity_threshold;
    associate(
        low, [](int) {}, threshold);
  }

  // The last resort across a long gap: a track that every round left coasting may take a
  // high-score detection no round took, by centre distance in its own box sizes, within a reach
  // that grows with the time between processed frames (people walk out of any IoU gate between
  // frames a second apart). Only leftovers on both sides: a detection an overlap could explain
  // was already taken, and a track found by overlap is not here. The clock is the gap, not the
  // time since the track's last match: at full rate a track lost for a few frames is the widened
  // IoU gate's business, and a reach grown with that time took far detections there (measured on
  // MOT15, in-sample: count error 23.7 / 42.9 % -> 27.4 / 48.0 % at intervals 1 / 5,
  // docs/events.md). Tentative tracks take part: at 1/10 rate most tracks are young, and leaving
  // them out lost 2 of the 13 points gained at interval 10 (same study).
  void distance_round() {
    collect_leftover_detections();
    if (rest.empty()) return;
    collect_coasting_tracks();

    candidates.clear();
    for (const int position : positions) {
      const Track& track = slots[order[position]];
      candidates.push_back(
          AssociationCandidate{track.predicted, step_frames, 0.F, &track.appearance});
    }
    round_matches.clear();
    associator.associate_by_distance(config, rest, candidates, round_matches);
    for (const AssociationMatch& m : round_matches) {
      high_taken[static_cast<std::size_t>(rest_index[static_cast<std::size_t>(m.detection)])] = 1;
      correct_track(slots[order[positions[m.candidate]]], rest[m.detection]);
    }
  }

  // The high-score detections no round took, into `rest` (their index in `high`: `rest_index`).
  void collect_leftover_detections() {
    rest.clear();
    rest_index.clear();
    for (std::size_t d = 0; d < high.size(); ++d) {
      if (high_taken[d]) continue;
      rest.push_back(high[d]);
      rest_index.push_back(static_cast<int>(d));
    }
  }

  void collect_coasting_tracks() {
    positions.clear();
    for (int t = 0; t < static_cast<int>(order.size()); ++t) {
      if (!slots[order[t]].matched_now()) positions.push_back(t);
    }
  }

  // One association round of `detections` against the tracks at `positions` (indices into
  // `order`); each match corrects its track at once. `take(d)` is told that detections[d] was
  // matched (the first round and the cascade mark it taken in `high`).
  template <typename Take>
  void associate(const std::vector<Detection>& detections, Take take) {
    associate(detections, take, config.affinity_threshold);
  }

  template <typename Take>
  void associate(const std::vector<Detection>& detections, Take take, double threshold) {
    candidates.clear();
    const auto noise_margin =
        static_cast<float>(config.noise_gate_factor * box_noise.median_offset());
    for (const int position : positions) {
      const Track& track = slots[order[position]];
      double gate_time =
          config.gate_clock == GateClock::frame_gap ? step_frames : track.frames_since_update;
      // The widening answers for the motion model's guess over the gap; where the image showed
      // where the track is, that guess was replaced (docs/full-rate.md, "The gate of a followed
      // track").
      if (track.observed_now && config.observed_gate_frames > 0.0)
        gate_time = std::min(gate_time, config.observed_gate_frames);
      candidates.push_back(
          AssociationCandidate{track.predicted, gate_time, noise_margin, &track.appearance});
    }
    round_matches.clear();
    associator.associate(config, threshold, detections, candidates, round_matches);
    handovers.clear();
    for (const AssociationMatch& m : round_matches) {
      take(m.detection);
      const int slot = order[positions[m.candidate]];
      if (looks_like_someone_else(config, slots[slot], detections[m.detection])) {
        handovers.push_back(Handover{m.detection, slot});
        continue;
      }
      correct_track(slots[slot], detections[m.detection]);
    }
    // After the round's other matches, so that a track they matched is not offered a second box.
    for (const Handover& h : handovers) {
      const Detection& detection = detections[h.detection];
      Track* owner = unmatched_lookalike(table_view(), detection, slots[h.slot]);
      correct_track(owner != nullptr ? *owner : slots[h.slot], detection);
    }
  }

  void correct_track(Track& track, const Detection& detection) {
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
  static void reupdate_from_observations(Track& track, KalmanPredictor& kalman, const Box& found) {
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

  // Whether another detection of this frame covers part of `detection` (kOccludedShare).
  bool overlapped(const Detection& detection) const {
    const auto covers = [&](const Detection& other) {
      const Box& a = other.box;
      const Box& b = detection.box;
      const bool itself = a.x == b.x && a.y == b.y && a.w == b.w && a.h == b.h;
      return !itself && covered_share(b, a) > kOccludedShare;
    };
    return std::any_of(high.begin(), high.end(), covers) ||
           std::any_of(low.begin(), low.end(), covers);
  }

  // Every high-score detection that no round took starts a tentative track (with a birth cut,
  // only the confident ones: a continuation needs less evidence than a new object).
  void start_tracks() {
    const float birth = extension
                            ? std::max(config.birth_threshold, extension->birth_cut(score_cut))
                            : config.birth_threshold;
    for (std::size_t d = 0; d < high.size(); ++d) {
      if (!high_taken[d] && high[d].score >= birth) start_track(high[d]);
    }
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
  void settle_and_report() {
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

  // The table as the identity passes see it (crossings.hpp, handback.hpp, reidentification.hpp).
  TrackTableView table_view() { return TrackTableView{slots, order, config, last_update_time}; }

  static TrackReport report(const Track& track) {
    return TrackReport{track.id,          current_box(track.predictor),
                       track.score,       track.class_id,
                       track.hit_streak,  track.age,
                       track.life.stage()};
  }

  bool confirmed(const Track& track) const {
    const TrackFacts facts = track.facts();
    if (!extension) {
      return confirmation.confirms(facts, StreamClock{frame_count, elapsed_frames}, true);
    }
    if (!extension->may_confirm(facts, score_cut)) return false;
    return confirmation.confirms(facts, StreamClock{frame_count, elapsed_frames},
                                 extension->may_confirm_by_duration(facts));
  }

  void release(int slot) {
    slots[slot].predictor.emplace<std::monostate>();
    slots[slot].life.remove();
    free_slots.push_back(slot);
  }

  double steps_until(double time_seconds) const {
    if (frame_count == 0) return 0.0;
    const double seconds = time_seconds - last_update_time;
    double steps = seconds * config.frame_rate;
    if (config.time_step == TimeStep::per_update && frame_count > 1 && last_gap_seconds > 0.0)
      steps = seconds / last_gap_seconds;
    return std::isfinite(steps) ? std::max(steps, 0.0) : 0.0;
  }

  // The tracks settle_and_report() reported are the live ones it left confirmed: a copy of each
  // one's motion model is advanced (peek), the track itself is not touched.
  void predict_reported(double steps, std::vector<TrackReport>& out, int min_hits) const {
    out.clear();
    for (const int slot : order) {
      const Track& track = slots[slot];
      if (track.life.stage() != TrackStage::confirmed || track.hit_streak < min_hits) continue;
      TrackReport ahead = report(track);
      ahead.box = peek(track.predictor, steps);
      if (is_finite(ahead.box)) out.push_back(ahead);
    }
  }

  const std::vector<TrackReport>& fill_table() {
    table.clear();
    for (const int slot : order) table.push_back(report(slots[slot]));
    return table;
  }

  TrackerConfig config;
  std::unique_ptr<TrackerExtension> extension;  // the study's rules; null in the product
  ConfirmationPolicy confirmation;
  // The track table: slots, the free ones, and the live ones oldest first (sort.py's list order).
  std::vector<Track> slots;
  std::vector<int> free_slots;
  std::vector<int> order;
  std::vector<Particle> particles;  // two buffers per slot for the particle predictor
  // One update's detections by role, and the association rounds' workspace.
  std::vector<Detection> high;
  std::vector<Detection> low;
  std::vector<char> high_taken;    // high[d] was matched by a round
  std::vector<char> hidden_flags;  // high's, then low's: partly covered by another detection
  std::vector<Detection> rest;     // the cascade's second level: detections left by the first
  std::vector<int> rest_index;     // their index in `high`
  std::vector<int> positions;      // the round's tracks, as indices into `order`
  std::vector<AssociationCandidate> candidates;
  std::vector<AssociationMatch> round_matches;
  std::vector<TrackReport> reports;
  std::vector<TrackReport> table;  // track_table()'s
  // A match held back by handback_gate until the round's other matches are made.
  struct Handover {
    int detection;
    int slot;
  };
  std::vector<Handover> handovers;
  Associator associator;
  BoxNoise box_noise;
  ScoreCut score_cut;
  bool cascades;              // the cascade round runs
  Reidentifier reidentifier;  // with the removed tracks it remembers (sized at construction)
  std::int32_t next_id{1};
  int frame_count{0};
  double elapsed_frames{0.0};  // nominal frames since the first update
  double step_frames{1.0};     // nominal frames since the previous update
  double previous_time{0.0};
  bool has_previous_time{false};
  double last_update_time{0.0};  // the time of the last update()
  double last_gap_seconds{0.0};  // between the last two updates
};

Tracker::Tracker(const TrackerConfig& config) : Tracker(config, nullptr) {}
Tracker::Tracker(const TrackerConfig& config, std::unique_ptr<TrackerExtension> extension)
    : state_(std::make_unique<State>(config, std::move(extension))) {}
Tracker::~Tracker() = default;
Tracker::Tracker(Tracker&&) noexcept = default;
Tracker& Tracker::operator=(Tracker&&) noexcept = default;

const std::vector<TrackReport>& Tracker::update(const std::vector<Detection>& detections,
                                                double time_seconds) {
  return state_->update(detections, time_seconds, nullptr);
}

const std::vector<TrackReport>& Tracker::update(const std::vector<Detection>& detections,
                                                double time_seconds,
                                                const std::vector<ObservedBox>& observed) {
  return state_->update(detections, time_seconds, observed.empty() ? nullptr : &observed);
}

void Tracker::reset() {
  state_->restart();
}

const TrackerConfig& Tracker::config() const {
  return state_->config;
}

const std::vector<TrackReport>& Tracker::track_table() {
  return state_->fill_table();
}

void Tracker::predict_reported(double steps, std::vector<TrackReport>& out, int min_hits) const {
  state_->predict_reported(steps, out, min_hits);
}

void Tracker::predict_reported_at(double time_seconds, std::vector<TrackReport>& out,
                                  int min_hits) const {
  state_->predict_reported(state_->steps_until(time_seconds), out, min_hits);
}

double Tracker::steps_until(double time_seconds) const {
  return state_->steps_until(time_seconds);
}

int Tracker::live_tracks() const {
  return static_cast<int>(state_->order.size());
}

}  // namespace rtmot::tracker
