#include "tracker/association.hpp"

#include <algorithm>

#include "tracker/affinity.hpp"

namespace rtmot::tracker {

Associator::Associator(int rows, int cols) {
  const auto cells = static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols);
  affinities_.reserve(cells);
  costs_.reserve(cells);
  row_hits_.reserve(static_cast<std::size_t>(rows));
  col_hits_.reserve(static_cast<std::size_t>(cols));
  assignment_.reserve(rows, cols);
}

void Associator::associate(const TrackerConfig& config, double threshold,
                           const std::vector<Detection>& detections,
                           const std::vector<AssociationCandidate>& candidates,
                           std::vector<AssociationMatch>& matches) {
  const int rows = static_cast<int>(detections.size());
  const int cols = static_cast<int>(candidates.size());
  if (rows == 0 || cols == 0) return;
  const auto at = [cols](int r, int c) { return static_cast<std::size_t>(r) * cols + c; };
  affinities_.resize(static_cast<std::size_t>(rows) * cols);
  row_hits_.assign(rows, 0);
  col_hits_.assign(cols, 0);
  int above = 0;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const double value = affinity(config, candidates[c].predicted, detections[r].box,
                                    candidates[c].gate_frames, candidates[c].noise_margin);
      affinities_[at(r, c)] = value;
      if (value > threshold) {
        ++row_hits_[r];
        ++col_hits_[c];
        ++above;
      }
    }
  }
  const bool one_to_one = above > 0 && *std::max_element(row_hits_.begin(), row_hits_.end()) == 1 &&
                          *std::max_element(col_hits_.begin(), col_hits_.end()) == 1;
  if (one_to_one) {
    for (int r = 0; r < rows; ++r) {
      for (int c = 0; c < cols; ++c) {
        if (affinities_[at(r, c)] > threshold) matches.push_back(AssociationMatch{r, c});
      }
    }
    return;
  }
  const double best = *std::max_element(affinities_.begin(), affinities_.end());
  if (!(best >= threshold)) return;  // no pair could pass the gate: skip the solver
  costs_.resize(affinities_.size());
  std::transform(affinities_.begin(), affinities_.end(), costs_.begin(),
                 [](double value) { return -value; });
  const std::vector<int>& assigned = assignment_.solve(costs_.data(), rows, cols);
  for (int r = 0; r < rows; ++r) {
    const int c = assigned[r];
    if (c >= 0 && affinities_[at(r, c)] >= threshold) matches.push_back(AssociationMatch{r, c});
  }
}

}  // namespace rtmot::tracker
