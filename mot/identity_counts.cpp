// Identity measures (Ristani et al., "Performance Measures and a Data Set for Multi-Target,
// Multi-Camera Tracking", 2016) as the devkit's IDmeasures: a gt and a result trajectory agree in
// a frame where both exist with IoU >= 0.5; trajectories are matched one-to-one to minimise
// IDFP + IDFN. The devkit solves that on an (n_gt + n_res)^2 matrix with "unmatched" blocks; it
// equals the maximum-weight matching of the n_gt x n_res agreement counts (IDFN = gt boxes -
// agreements kept, IDFP = result boxes - agreements kept), which is the smaller problem we solve.
#include "mot/box_iou.hpp"
#include "mot/scorer.hpp"
#include "tracker/linear_assignment.hpp"

namespace rtmot::mot {

IdentityCounts count_identity(const PreparedSequence& sequence) {
  const int gt_ids = sequence.num_gt_ids;
  const int result_ids = sequence.num_result_ids;
  std::vector<double> agreements(static_cast<std::size_t>(gt_ids) * result_ids, 0.0);
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
          agreements[static_cast<std::size_t>(gt.ids[g]) * result_ids + results.ids[r]] += 1.0;
        }
      }
    }
  }

  std::int64_t kept = 0;
  if (gt_ids > 0 && result_ids > 0) {
    std::vector<double> cost(agreements.size());
    for (std::size_t i = 0; i < cost.size(); ++i) cost[i] = -agreements[i];
    tracker::LinearAssignment solver;
    const auto& assignment = solver.solve(cost.data(), gt_ids, result_ids);
    for (int g = 0; g < gt_ids; ++g) {
      if (assignment[g] >= 0) {
        kept += static_cast<std::int64_t>(
            agreements[static_cast<std::size_t>(g) * result_ids + assignment[g]]);
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
