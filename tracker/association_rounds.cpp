// Tracker::State's association rounds (tracker_state.hpp): the update's detections by role (high,
// low, partly covered) and the rounds that match them to tracks, each match correcting its track.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "tracker/box_geometry.hpp"
#include "tracker/handback.hpp"
#include "tracker/tracker_extension.hpp"
#include "tracker/tracker_state.hpp"

namespace rtmot::tracker {
namespace {

// A detection whose box another detection covers this much of shows someone else's pixels too:
// its appearance does not teach its track (a tenth of a person is an arm or a bag).
constexpr float kOccludedShare = 0.1F;

bool usable(const Detection& detection) {
  return is_finite(detection.box) && detection.box.w > 0.F && detection.box.h > 0.F &&
         std::isfinite(detection.score);
}

}  // namespace

// High-score detections may start and continue tracks; low ones (ByteTrack) only continue them.
// High means at or above both the absolute and the relative cut.
void Tracker::State::split_by_score(const std::vector<Detection>& detections) {
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
void Tracker::State::forget_hidden_appearances() {
  std::size_t hidden = 0;
  for (const Detection& d : high) hidden_flags[hidden++] = d.appearance.valid && overlapped(d);
  for (const Detection& d : low) hidden_flags[hidden++] = d.appearance.valid && overlapped(d);
  hidden = 0;
  for (Detection& d : high) d.appearance.valid = d.appearance.valid && !hidden_flags[hidden++];
  for (Detection& d : low) d.appearance.valid = d.appearance.valid && !hidden_flags[hidden++];
}

// Whether another detection of this frame covers part of `detection` (kOccludedShare).
bool Tracker::State::overlapped(const Detection& detection) const {
  const auto covers = [&](const Detection& other) {
    const Box& a = other.box;
    const Box& b = detection.box;
    const bool itself = a.x == b.x && a.y == b.y && a.w == b.w && a.h == b.h;
    return !itself && covered_share(b, a) > kOccludedShare;
  };
  return std::any_of(high.begin(), high.end(), covers) ||
         std::any_of(low.begin(), low.end(), covers);
}

// SORT's association: the high-score detections against every live track (with the cascade,
// against the tracks matched in the previous update only; with confirmed_tracks_first, against
// the confirmed ones only).
void Tracker::State::first_round() {
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
void Tracker::State::cascade_round() {
  collect_leftover_detections();
  collect_coasting_tracks();
  associate(rest, [&](int r) {
    high_taken[static_cast<std::size_t>(rest_index[static_cast<std::size_t>(r)])] = 1;
  });
}

// ByteTrack: low-score detections may only continue the tracks the rounds before left coasting
// (with second_round_recent_only, those of them that were confirmed and matched last update).
void Tracker::State::second_round() {
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
void Tracker::State::distance_round() {
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
void Tracker::State::collect_leftover_detections() {
  rest.clear();
  rest_index.clear();
  for (std::size_t d = 0; d < high.size(); ++d) {
    if (high_taken[d]) continue;
    rest.push_back(high[d]);
    rest_index.push_back(static_cast<int>(d));
  }
}

void Tracker::State::collect_coasting_tracks() {
  positions.clear();
  for (int t = 0; t < static_cast<int>(order.size()); ++t) {
    if (!slots[order[t]].matched_now()) positions.push_back(t);
  }
}

// One association round of `detections` against the tracks at `positions` (indices into
// `order`); each match corrects its track at once. `take(d)` is told that detections[d] was
// matched (the first round and the cascade mark it taken in `high`).
template <typename Take>
void Tracker::State::associate(const std::vector<Detection>& detections, Take take) {
  associate(detections, take, config.affinity_threshold);
}

template <typename Take>
void Tracker::State::associate(const std::vector<Detection>& detections, Take take,
                               double threshold) {
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

}  // namespace rtmot::tracker
