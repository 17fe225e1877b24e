#include "tracker/tracker.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "tracker/box_geometry.hpp"
#include "tracker/predictor.hpp"
#include "tracker/tracker_extension.hpp"
#include "tracker/tracker_state.hpp"

namespace rtmot::tracker {
namespace {

constexpr int kTypicalSceneSize = 64;

const TrackerConfig& validated(const TrackerConfig& config) {
  if (const auto problem = config_problem(config))
    throw std::invalid_argument("tracker: " + *problem);
  return config;
}

}  // namespace

Tracker::State::State(const TrackerConfig& c, std::unique_ptr<TrackerExtension> e)
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

void Tracker::State::restart() {
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
const std::vector<TrackReport>& Tracker::State::update(const std::vector<Detection>& detections,
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

double Tracker::State::step_length(double time_seconds) {
  if (config.time_step == TimeStep::per_update) return 1.0;
  double dt = 1.0;
  if (has_previous_time) dt = (time_seconds - previous_time) * config.frame_rate;
  previous_time = time_seconds;
  has_previous_time = true;
  return std::isfinite(dt) ? std::max(dt, 0.0) : 1.0;
}

double Tracker::State::steps_until(double time_seconds) const {
  if (frame_count == 0) return 0.0;
  const double seconds = time_seconds - last_update_time;
  double steps = seconds * config.frame_rate;
  if (config.time_step == TimeStep::per_update && frame_count > 1 && last_gap_seconds > 0.0)
    steps = seconds / last_gap_seconds;
  return std::isfinite(steps) ? std::max(steps, 0.0) : 0.0;
}

// The tracks settle_and_report() reported are the live ones it left confirmed: a copy of each
// one's motion model is advanced (peek), the track itself is not touched.
void Tracker::State::predict_reported(double steps, std::vector<TrackReport>& out,
                                      int min_hits) const {
  out.clear();
  for (const int slot : order) {
    const Track& track = slots[slot];
    if (track.life.stage() != TrackStage::confirmed || track.hit_streak < min_hits) continue;
    TrackReport ahead = report(track);
    ahead.box = peek(track.predictor, steps);
    if (is_finite(ahead.box)) out.push_back(ahead);
  }
}

const std::vector<TrackReport>& Tracker::State::fill_table() {
  table.clear();
  for (const int slot : order) table.push_back(report(slots[slot]));
  return table;
}

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
