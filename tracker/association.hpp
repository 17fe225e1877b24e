#pragma once
// One association round: detections against candidate tracks, as sort.py's
// associate_detections_to_trackers, for any affinity.
#include <cstddef>
#include <vector>

#include "tracker/box.hpp"
#include "tracker/linear_assignment.hpp"
#include "tracker/tracker_config.hpp"

namespace rtmot::tracker {

/// What association needs to know of a track.
struct AssociationCandidate {
  Box predicted;
  double gate_frames{1.0};  // nominal frames that widen its gate (TrackerConfig::gate_clock)
  float noise_margin{0.F};  // the gate margin the stream's box noise asks for (noise_gate_factor)
  const Appearance* appearance{nullptr};  // the track's, when it has one
};

/// The distance round's pairs differ in height by at most this factor: a far detection of a
/// person nearer to or further from the camera is another person (the events' link uses 1.5 too).
inline constexpr double kDistanceRoundHeightRatio = 1.5;

/// How far `detection`'s centre lies from `predicted`'s, in `predicted`'s width and height.
double normalised_centre_distance(const Box& predicted, const Box& detection);

struct AssociationMatch {
  int detection;  // index into the detections
  int candidate;  // index into the candidates
};

class Associator {
 public:
  /// Reserves a workspace for up to rows x cols matrices; larger ones grow it once.
  Associator(int rows, int cols);

  /// Appends to `matches` the pairs whose affinity reaches `threshold`; where the candidate and the
  /// detection both have an appearance, config's appearance gate and weight apply. When every
  /// detection and every candidate has at most one partner above the threshold, those pairs are
  /// taken directly (sort.py's shortcut); otherwise the optimal assignment decides.
  void associate(const TrackerConfig& config, double threshold,
                 const std::vector<Detection>& detections,
                 const std::vector<AssociationCandidate>& candidates,
                 std::vector<AssociationMatch>& matches);

  /// The same round by centre distance (TrackerConfig::distance_gate_per_frame): a pair is
  /// possible when the detection's centre lies within min(distance_gate_per_frame x
  /// gate_frames, distance_gate_max) of the candidate's predicted centre, in the predicted box's
  /// sizes, and their heights are within kDistanceRoundHeightRatio; the assignment prefers the
  /// closer pairs. The appearance weighs in as in associate().
  void associate_by_distance(const TrackerConfig& config, const std::vector<Detection>& detections,
                             const std::vector<AssociationCandidate>& candidates,
                             std::vector<AssociationMatch>& matches);

 private:
  template <typename AffinityOf>
  void fill_and_solve(const TrackerConfig& config, const std::vector<Detection>& detections,
                      const std::vector<AssociationCandidate>& candidates, double threshold,
                      const AffinityOf& affinity_of, std::vector<AssociationMatch>& matches);
  // Appends the matches for the affinities_ and preferences_ already filled (rows x cols,
  // row-major): the affinities decide which pairs are possible, the preferences which of them
  // the assignment takes.
  void solve(double threshold, int rows, int cols, std::vector<AssociationMatch>& matches);
  // Each row's and column's pairs above the threshold.
  void count_hits(double threshold, int rows, int cols);
  // Makes impossible the pairs in beyond_gate_ whose row or column has another pair above the
  // threshold (with rival_must_look_alike, another such pair within the gate: alike_); whether
  // any was.
  bool refuse_contested_beyond_gate(double threshold, int rows, int cols,
                                    bool rival_must_look_alike);

  std::vector<double> affinities_;
  std::vector<double> preferences_;
  // The pairs (row-major indices) the affinity allows but the appearance puts beyond the gate,
  // which appearance_gate_contested has not yet refused: usually none, so a round without them
  // costs nothing more.
  std::vector<std::size_t> beyond_gate_;
  // appearance_gate_rival_alike: per pair (row-major), whether the appearance put it within the
  // gate.
  std::vector<char> alike_;
  std::vector<double> costs_;
  std::vector<int> row_hits_;
  std::vector<int> col_hits_;
  LinearAssignment assignment_;
};

}  // namespace rtmot::tracker
