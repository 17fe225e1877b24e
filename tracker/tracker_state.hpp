#pragma once
// The Tracker's state: its track table, the association rounds' workspace and its clocks. The
// methods are defined by idea: construction, restart, the update's order of passes and the public
// API in tracker.cpp; the detections' roles and the association rounds in association_rounds.cpp;
// the tracks' life (predict, correct, start, settle and report) in track_life.cpp. Internal to
// tracker/.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "tracker/association.hpp"
#include "tracker/box.hpp"
#include "tracker/box_noise.hpp"
#include "tracker/confirmation_policy.hpp"
#include "tracker/particle_predictor.hpp"
#include "tracker/reidentification.hpp"
#include "tracker/score_cut.hpp"
#include "tracker/track.hpp"
#include "tracker/track_table.hpp"
#include "tracker/tracker.hpp"
#include "tracker/tracker_config.hpp"

namespace rtmot::tracker {

// The update is a sequence of named passes over a table of track slots (see update()). Every
// buffer below is sized at construction; a pass only clears and refills them. The identity passes
// that decide on the looks alone (the hand-back's choice of owner, crossing resolution,
// re-identification) live in their own files and see the table through a TrackTableView.
struct Tracker::State {
  // tracker.cpp: construction, restart, the update's order of passes, what the public API reads.
  State(const TrackerConfig& c, std::unique_ptr<TrackerExtension> e);
  void restart();
  const std::vector<TrackReport>& update(const std::vector<Detection>& detections,
                                         double time_seconds,
                                         const std::vector<ObservedBox>* observed);
  double step_length(double time_seconds);
  double steps_until(double time_seconds) const;
  void predict_reported(double steps, std::vector<TrackReport>& out, int min_hits) const;
  const std::vector<TrackReport>& fill_table();

  // association_rounds.cpp: the detections' roles and the rounds that match them to tracks.
  void split_by_score(const std::vector<Detection>& detections);
  void forget_hidden_appearances();
  bool overlapped(const Detection& detection) const;
  void first_round();
  void cascade_round();
  void second_round();
  void distance_round();
  void collect_leftover_detections();
  void collect_coasting_tracks();
  // Defined in association_rounds.cpp, where every round that calls it is.
  template <typename Take>
  void associate(const std::vector<Detection>& detections, Take take);
  template <typename Take>
  void associate(const std::vector<Detection>& detections, Take take, double threshold);

  // track_life.cpp: predict, correct, start, settle and report, release.
  void predict_tracks(double dt);
  void correct_with_observed(const std::vector<ObservedBox>& observed);
  void correct_track(Track& track, const Detection& detection);
  static void reupdate_from_observations(Track& track, KalmanPredictor& kalman, const Box& found);
  void start_tracks();
  void start_track(const Detection& detection);
  void settle_and_report();
  static TrackReport report(const Track& track);
  bool confirmed(const Track& track) const;
  void release(int slot);

  // The table as the identity passes see it (crossings.hpp, handback.hpp, reidentification.hpp).
  TrackTableView table_view() { return TrackTableView{slots, order, config, last_update_time}; }

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

}  // namespace rtmot::tracker
