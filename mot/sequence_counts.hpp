#pragma once
// The additive raw counts behind every metric. Scores of several sequences pooled = scores of the
// sum of their counts (the devkit's and TrackEval's way to compute OVERALL).
#include <array>
#include <cstdint>

namespace rtmot::mot {

/// HOTA is evaluated at alpha = 0.05, 0.10, ..., 0.95.
constexpr int kHotaAlphaCount = 19;
inline double hota_alpha(int index) {
  return 0.05 + 0.05 * index;
}  // as numpy.arange

struct ClearCounts {
  std::int64_t gt_detections{0};
  std::int64_t true_positives{0};
  std::int64_t false_positives{0};
  std::int64_t false_negatives{0};
  std::int64_t id_switches{0};
  std::int64_t fragmentations{0};
  std::int64_t gt_tracks{0};
  std::int64_t mostly_tracked{0};
  std::int64_t partly_tracked{0};
  std::int64_t mostly_lost{0};
  std::int64_t frames{0};
  double iou_sum{0.0};  // over the true positives
};

struct IdentityCounts {
  std::int64_t true_positives{0};
  std::int64_t false_positives{0};
  std::int64_t false_negatives{0};
};

struct HotaCounts {
  using PerAlpha = std::array<double, kHotaAlphaCount>;
  PerAlpha true_positives{};
  PerAlpha false_negatives{};
  PerAlpha false_positives{};
  /// Sum over true positives of their pair's association IoU (AssA = this / TP).
  PerAlpha association_sum{};
  /// Sum over true positives of their box IoU (LocA = this / TP).
  PerAlpha localization_sum{};
};

struct SequenceCounts {
  ClearCounts clear;
  IdentityCounts identity;
  HotaCounts hota;
};

SequenceCounts& operator+=(SequenceCounts& total, const SequenceCounts& more);

}  // namespace rtmot::mot
