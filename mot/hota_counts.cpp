// HOTA (Luiten et al., "HOTA: A Higher Order Metric for Evaluating Multi-Object Tracking", IJCV
// 2020) as TrackEval computes it: a first pass measures how well each gt/result id pair is aligned
// over the whole sequence; each frame is then matched to maximise alignment x IoU, and for each
// alpha the pairs with IoU >= alpha are the true positives.
// Id pairs are kept in hash maps, holding only pairs that overlap in some frame: memory grows with
// those, not with gt ids x result ids. Sums run in the dense loops' order (frames, then pairs in
// gt-major order), so every figure is bit-identical to the dense computation.
#include <algorithm>
#include <array>
#include <limits>
#include <unordered_map>

#include "mot/box_iou.hpp"
#include "mot/scorer.hpp"
#include "tracker/linear_assignment.hpp"

namespace rtmot::mot {

namespace {

constexpr double kEpsilon = std::numeric_limits<double>::epsilon();

void fill_similarity(const TimestepBoxes& gt, const TimestepBoxes& results,
                     std::vector<double>& similarity) {
  const std::size_t cols = results.ids.size();
  similarity.assign(gt.ids.size() * cols, 0.0);
  for (std::size_t g = 0; g < gt.ids.size(); ++g) {
    for (std::size_t r = 0; r < cols; ++r) {
      similarity[g * cols + r] = box_iou(gt.boxes[g], results.boxes[r]);
    }
  }
}

}  // namespace

HotaCounts count_hota(const PreparedSequence& sequence) {
  HotaCounts counts;
  const std::size_t gt_ids = static_cast<std::size_t>(sequence.num_gt_ids);
  const std::size_t result_ids = static_cast<std::size_t>(sequence.num_result_ids);
  std::unordered_map<std::size_t, double> potential;  // gt * result_ids + result; absent: 0
  std::vector<double> gt_id_count(gt_ids, 0.0);
  std::vector<double> result_id_count(result_ids, 0.0);
  std::vector<double> similarity;
  std::vector<double> row_sum;
  std::vector<double> col_sum;

  // Pass 1: soft co-occurrence of id pairs, each frame's IoU normalised by its competitors.
  for (std::size_t t = 0; t < sequence.gt.size(); ++t) {
    const TimestepBoxes& gt = sequence.gt[t];
    const TimestepBoxes& results = sequence.results[t];
    for (const int id : gt.ids) gt_id_count[static_cast<std::size_t>(id)] += 1.0;
    for (const int id : results.ids) result_id_count[static_cast<std::size_t>(id)] += 1.0;
    if (gt.ids.empty() || results.ids.empty()) continue;
    fill_similarity(gt, results, similarity);
    const std::size_t rows = gt.ids.size();
    const std::size_t cols = results.ids.size();
    row_sum.assign(rows, 0.0);
    col_sum.assign(cols, 0.0);
    for (std::size_t g = 0; g < rows; ++g) {
      for (std::size_t r = 0; r < cols; ++r) {
        row_sum[g] += similarity[g * cols + r];
        col_sum[r] += similarity[g * cols + r];
      }
    }
    for (std::size_t g = 0; g < rows; ++g) {
      for (std::size_t r = 0; r < cols; ++r) {
        const double value = similarity[g * cols + r];
        if (value == 0.0) continue;  // adds nothing: no entry for pairs that never overlap
        const double denominator = row_sum[g] + col_sum[r] - value;
        if (denominator > kEpsilon) {
          potential[static_cast<std::size_t>(gt.ids[g]) * result_ids +
                    static_cast<std::size_t>(results.ids[r])] += value / denominator;
        }
      }
    }
  }
  std::unordered_map<std::size_t, double> alignment;  // absent: 0
  alignment.reserve(potential.size());
  for (const auto& [pair, p] : potential) {
    alignment[pair] = p / (gt_id_count[pair / result_ids] + result_id_count[pair % result_ids] - p);
  }
  const auto alignment_of = [&](std::size_t pair) {
    const auto found = alignment.find(pair);
    return found == alignment.end() ? 0.0 : found->second;
  };

  // Pass 2: per-frame matching, then true positives per alpha.
  std::unordered_map<std::size_t, std::array<double, kHotaAlphaCount>> matches;
  tracker::LinearAssignment solver;
  std::vector<double> cost;
  for (std::size_t t = 0; t < sequence.gt.size(); ++t) {
    const TimestepBoxes& gt = sequence.gt[t];
    const TimestepBoxes& results = sequence.results[t];
    const auto gt_count = static_cast<double>(gt.ids.size());
    const auto result_count = static_cast<double>(results.ids.size());
    if (gt.ids.empty() || results.ids.empty()) {
      for (int a = 0; a < kHotaAlphaCount; ++a) {
        counts.false_negatives[a] += gt_count;
        counts.false_positives[a] += result_count;
      }
      continue;
    }
    fill_similarity(gt, results, similarity);
    const std::size_t rows = gt.ids.size();
    const std::size_t cols = results.ids.size();
    cost.resize(rows * cols);
    for (std::size_t g = 0; g < rows; ++g) {
      for (std::size_t r = 0; r < cols; ++r) {
        const std::size_t pair = static_cast<std::size_t>(gt.ids[g]) * result_ids +
                                 static_cast<std::size_t>(results.ids[r]);
        cost[g * cols + r] = -alignment_of(pair) * similarity[g * cols + r];
      }
    }
    const auto& assignment =
        solver.solve(cost.data(), static_cast<int>(rows), static_cast<int>(cols));
    for (int a = 0; a < kHotaAlphaCount; ++a) {
      const double alpha = hota_alpha(a);
      double matched = 0.0;
      for (std::size_t g = 0; g < rows; ++g) {
        const int r = assignment[g];
        if (r < 0) continue;
        const double iou = similarity[g * cols + static_cast<std::size_t>(r)];
        if (iou < alpha - kEpsilon) continue;
        matched += 1.0;
        counts.localization_sum[a] += iou;
        matches[static_cast<std::size_t>(gt.ids[g]) * result_ids +
                static_cast<std::size_t>(results.ids[r])][a] += 1.0;
      }
      counts.true_positives[a] += matched;
      counts.false_negatives[a] += gt_count - matched;
      counts.false_positives[a] += result_count - matched;
    }
  }

  // Association: each true positive weighted by its id pair's Jaccard over the sequence.
  std::vector<std::size_t> matched_pairs;
  matched_pairs.reserve(matches.size());
  for (const auto& entry : matches) matched_pairs.push_back(entry.first);
  std::sort(matched_pairs.begin(), matched_pairs.end());  // the dense loops' order
  for (int a = 0; a < kHotaAlphaCount; ++a) {
    double sum = 0.0;
    for (const std::size_t pair : matched_pairs) {
      const double m = matches[pair][a];
      if (m == 0.0) continue;
      const std::size_t g = pair / result_ids;
      const std::size_t r = pair % result_ids;
      sum += m * m / std::max(1.0, gt_id_count[g] + result_id_count[r] - m);
    }
    counts.association_sum[a] = sum;
  }
  return counts;
}

}  // namespace rtmot::mot
