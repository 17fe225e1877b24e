// Identity measures (Ristani et al., "Performance Measures and a Data Set for Multi-Target,
// Multi-Camera Tracking", 2016) as the devkit's IDmeasures: a gt and a result trajectory agree in
// a frame where both exist with IoU >= 0.5; trajectories are matched one-to-one to minimise
// IDFP + IDFN. The devkit solves that on an (n_gt + n_res)^2 matrix with "unmatched" blocks; it
// equals the maximum-weight matching of the n_gt x n_res agreement counts (IDFN = gt boxes -
// agreements kept, IDFP = result boxes - agreements kept), which is the smaller problem we solve.
// Smaller still: only pairs that agree at least once can add to the matching, so it splits into
// the connected components of the agreement graph, each solved alone. Memory grows with the
// agreeing pairs, not with gt ids x result ids (60k result ids no longer need gigabytes); the
// matching's weight is an integer, so the result is exactly the dense solution's.
#include <algorithm>
#include <numeric>
#include <unordered_map>

#include "mot/box_iou.hpp"
#include "mot/scorer.hpp"
#include "tracker/linear_assignment.hpp"

namespace rtmot::mot {
namespace {

// Union-find over gt ids (0..G-1) and result ids (G..G+R-1).
class Components {
 public:
  explicit Components(std::size_t nodes) : parent_(nodes) {
    std::iota(parent_.begin(), parent_.end(), std::size_t{0});
  }
  std::size_t root(std::size_t node) {
    while (parent_[node] != node) node = parent_[node] = parent_[parent_[node]];
    return node;
  }
  void join(std::size_t a, std::size_t b) { parent_[root(a)] = root(b); }

 private:
  std::vector<std::size_t> parent_;
};

}  // namespace

IdentityCounts count_identity(const PreparedSequence& sequence) {
  const auto gt_ids = static_cast<std::uint64_t>(sequence.num_gt_ids);
  const auto result_ids = static_cast<std::uint64_t>(sequence.num_result_ids);
  std::unordered_map<std::uint64_t, double> agreements;  // gt * result_ids + result -> frames
  std::int64_t gt_boxes = 0;
  std::int64_t result_boxes = 0;
  for (std::size_t t = 0; t < sequence.gt.size(); ++t) {
    const TimestepBoxes& gt = sequence.gt[t];
    const TimestepBoxes& results = sequence.results[t];
    gt_boxes += static_cast<std::int64_t>(gt.ids.size());
    result_boxes += static_cast<std::int64_t>(results.ids.size());
    for (std::size_t g = 0; g < gt.ids.size(); ++g) {
      for (std::size_t r = 0; r < results.ids.size(); ++r) {
        if (box_iou(gt.boxes[g], results.boxes[r]) >= 0.5) {
          agreements[static_cast<std::uint64_t>(gt.ids[g]) * result_ids +
                     static_cast<std::uint64_t>(results.ids[r])] += 1.0;
        }
      }
    }
  }

  // Group the agreeing pairs by component; ids without any agreement match nothing.
  Components components(gt_ids + result_ids);
  for (const auto& [pair, count] : agreements)
    components.join(pair / result_ids, gt_ids + pair % result_ids);
  std::unordered_map<std::size_t, std::vector<std::uint64_t>> pairs_of;
  for (const auto& [pair, count] : agreements)
    pairs_of[components.root(pair / result_ids)].push_back(pair);

  std::int64_t kept = 0;
  tracker::LinearAssignment solver;
  std::vector<double> cost;
  for (auto& [root, pairs] : pairs_of) {
    std::sort(pairs.begin(), pairs.end());
    std::vector<std::uint64_t> rows;
    std::vector<std::uint64_t> cols;
    for (const std::uint64_t pair : pairs) {
      rows.push_back(pair / result_ids);
      cols.push_back(pair % result_ids);
    }
    std::sort(rows.begin(), rows.end());
    rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
    std::sort(cols.begin(), cols.end());
    cols.erase(std::unique(cols.begin(), cols.end()), cols.end());
    const auto index_in = [](const std::vector<std::uint64_t>& ids, std::uint64_t id) {
      return static_cast<std::size_t>(std::lower_bound(ids.begin(), ids.end(), id) - ids.begin());
    };
    cost.assign(rows.size() * cols.size(), 0.0);
    for (const std::uint64_t pair : pairs) {
      cost[index_in(rows, pair / result_ids) * cols.size() + index_in(cols, pair % result_ids)] =
          -agreements.at(pair);
    }
    const auto& assignment =
        solver.solve(cost.data(), static_cast<int>(rows.size()), static_cast<int>(cols.size()));
    for (std::size_t g = 0; g < rows.size(); ++g) {
      if (assignment[g] >= 0) {
        kept += static_cast<std::int64_t>(
            -cost[g * cols.size() + static_cast<std::size_t>(assignment[g])]);
      }
    }
  }
  IdentityCounts counts;
  counts.true_positives = kept;
  counts.false_negatives = gt_boxes - kept;
  counts.false_positives = result_boxes - kept;
  return counts;
}

}  // namespace rtmot::mot
