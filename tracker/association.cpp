#include "tracker/association.hpp"

#include <algorithm>
#include <cmath>

#include "tracker/affinity.hpp"

namespace rtmot::tracker {
namespace {

// Below every threshold: the pair is impossible (the appearance gate).
constexpr double kImpossible = -1.0;

// What the appearance said of one pair: nothing (one side has none), alike (within the gate) or
// unlike (beyond it).
enum class GateVerdict { unseen, within, beyond };

// The matrices are rows (detections) x cols (candidates), row-major.
std::size_t cell(int r, int c, int cols) {
  return static_cast<std::size_t>(r) * cols + c;
}

// The appearance's say in one pair, where both sides have one: beyond the gate the pair is
// impossible (or, with appearance_gate_contested, marked beyond it: whether it is refused waits
// for its rivals); otherwise the assignment's preference is the affinity scaled down by the
// distance (relative: pairs of large and small affinities are scaled alike, for every affinity
// kind). Returns what the appearance said of the pair.
GateVerdict weigh_appearance(const TrackerConfig& config, const AssociationCandidate& candidate,
                             const Detection& detection, double& value, double& preference) {
  if (candidate.appearance == nullptr || !candidate.appearance->valid ||
      !detection.appearance.valid)
    return GateVerdict::unseen;
  const double distance = appearance_distance(*candidate.appearance, detection.appearance);
  GateVerdict verdict = GateVerdict::within;
  if (distance > config.appearance_gate) {
    if (!config.appearance_gate_contested) {
      value = preference = kImpossible;
      return GateVerdict::beyond;
    }
    verdict = GateVerdict::beyond;
  }
  preference = value * (1.0 - config.appearance_weight * distance);
  return verdict;
}

}  // namespace

Associator::Associator(int rows, int cols) {
  const auto cells = static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols);
  affinities_.reserve(cells);
  preferences_.reserve(cells);
  beyond_gate_.reserve(cells);
  alike_.reserve(cells);
  costs_.reserve(cells);
  row_hits_.reserve(static_cast<std::size_t>(rows));
  col_hits_.reserve(static_cast<std::size_t>(cols));
  assignment_.reserve(rows, cols);
}

// Fills the detections x candidates affinities and preferences (row-major), counts each row's and
// column's pairs above the threshold (what tells a one-to-one frame from one the solver must
// settle), refuses the contested pairs beyond the appearance gate (appearance_gate_contested), and
// solves.
template <typename AffinityOf>
void Associator::fill_and_solve(const TrackerConfig& config,
                                const std::vector<Detection>& detections,
                                const std::vector<AssociationCandidate>& candidates,
                                double threshold, const AffinityOf& affinity_of,
                                std::vector<AssociationMatch>& matches) {
  const int rows = static_cast<int>(detections.size());
  const int cols = static_cast<int>(candidates.size());
  if (rows == 0 || cols == 0) return;
  affinities_.resize(static_cast<std::size_t>(rows) * cols);
  preferences_.resize(affinities_.size());
  beyond_gate_.clear();
  const bool rival_must_look_alike = config.appearance_gate_rival_alike;
  if (rival_must_look_alike) alike_.assign(affinities_.size(), 0);
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      double value = affinity_of(r, c);
      double preference = value;
      const GateVerdict verdict =
          weigh_appearance(config, candidates[c], detections[r], value, preference);
      const std::size_t i = cell(r, c, cols);
      affinities_[i] = value;
      preferences_[i] = preference;
      if (verdict == GateVerdict::beyond && value > threshold) beyond_gate_.push_back(i);
      if (rival_must_look_alike && verdict == GateVerdict::within) alike_[i] = 1;
    }
  }
  count_hits(threshold, rows, cols);
  if (!beyond_gate_.empty() &&
      refuse_contested_beyond_gate(threshold, rows, cols, rival_must_look_alike)) {
    count_hits(threshold, rows, cols);
  }
  solve(threshold, rows, cols, matches);
}

void Associator::count_hits(double threshold, int rows, int cols) {
  row_hits_.assign(rows, 0);
  col_hits_.assign(cols, 0);
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      if (affinities_[cell(r, c, cols)] > threshold) {
        ++row_hits_[r];
        ++col_hits_[c];
      }
    }
  }
}

bool Associator::refuse_contested_beyond_gate(double threshold, int rows, int cols,
                                              bool rival_must_look_alike) {
  // A rival that looks alike: another pair of the row or column the affinity allows and the
  // appearance put within the gate. Searched only for the few pairs beyond the gate.
  const auto has_alike_rival = [&](int r, int c) {
    for (int other = 0; other < cols; ++other) {
      if (other != c && alike_[cell(r, other, cols)] &&
          affinities_[cell(r, other, cols)] > threshold)
        return true;
    }
    for (int other = 0; other < rows; ++other) {
      if (other != r && alike_[cell(other, c, cols)] &&
          affinities_[cell(other, c, cols)] > threshold)
        return true;
    }
    return false;
  };
  bool refused = false;
  for (const std::size_t i : beyond_gate_) {
    const auto r = static_cast<int>(i / static_cast<std::size_t>(cols));
    const auto c = static_cast<int>(i % static_cast<std::size_t>(cols));
    const bool contested = row_hits_[r] > 1 || col_hits_[c] > 1;
    if (contested && (!rival_must_look_alike || has_alike_rival(r, c))) {
      affinities_[i] = preferences_[i] = kImpossible;
      refused = true;
    }
  }
  return refused;
}

void Associator::associate(const TrackerConfig& config, double threshold,
                           const std::vector<Detection>& detections,
                           const std::vector<AssociationCandidate>& candidates,
                           std::vector<AssociationMatch>& matches) {
  fill_and_solve(
      config, detections, candidates, threshold,
      [&](int r, int c) {
        return affinity(config, candidates[c].predicted, detections[r].box,
                        candidates[c].gate_frames, candidates[c].noise_margin);
      },
      matches);
}

double normalised_centre_distance(const Box& predicted, const Box& detection) {
  const double dx = (double{detection.center_x()} - predicted.center_x()) / predicted.w;
  const double dy = (double{detection.center_y()} - predicted.center_y()) / predicted.h;
  return std::hypot(dx, dy);
}

void Associator::associate_by_distance(const TrackerConfig& config,
                                       const std::vector<Detection>& detections,
                                       const std::vector<AssociationCandidate>& candidates,
                                       std::vector<AssociationMatch>& matches) {
  // In (0, 1], larger when closer; -1 (below the threshold 0) when out of reach.
  fill_and_solve(
      config, detections, candidates, 0.0,
      [&](int r, int c) {
        const Box& predicted = candidates[c].predicted;
        const Box& box = detections[r].box;
        const double reach = std::min(config.distance_gate_per_frame * candidates[c].gate_frames,
                                      config.distance_gate_max);
        const double distance = normalised_centre_distance(predicted, box);
        const double heights = double{box.h} / predicted.h;
        const bool possible = distance <= reach && heights <= kDistanceRoundHeightRatio &&
                              heights >= 1.0 / kDistanceRoundHeightRatio;
        return possible ? 1.0 / (1.0 + distance) : kImpossible;
      },
      matches);
}

void Associator::solve(double threshold, int rows, int cols,
                       std::vector<AssociationMatch>& matches) {
  const bool any_hit = std::any_of(row_hits_.begin(), row_hits_.end(), [](int n) { return n > 0; });
  const bool one_to_one = any_hit && *std::max_element(row_hits_.begin(), row_hits_.end()) == 1 &&
                          *std::max_element(col_hits_.begin(), col_hits_.end()) == 1;
  if (one_to_one) {
    for (int r = 0; r < rows; ++r) {
      for (int c = 0; c < cols; ++c) {
        if (affinities_[cell(r, c, cols)] > threshold) matches.push_back(AssociationMatch{r, c});
      }
    }
    return;
  }
  const double best = *std::max_element(affinities_.begin(), affinities_.end());
  if (!(best >= threshold)) return;  // no pair could pass the gate: skip the solver
  costs_.resize(affinities_.size());
  std::transform(preferences_.begin(), preferences_.end(), costs_.begin(),
                 [](double value) { return -value; });
  const std::vector<int>& assigned = assignment_.solve(costs_.data(), rows, cols);
  for (int r = 0; r < rows; ++r) {
    const int c = assigned[r];
    if (c >= 0 && affinities_[cell(r, c, cols)] >= threshold)
      matches.push_back(AssociationMatch{r, c});
  }
}

}  // namespace rtmot::tracker
