#pragma once
// Confidence cuts relative to the stream's own recent scores, so that no setting assumes a score
// scale (a Faster R-CNN's 0.5..1, a DPM's -0.5..5, an SSD's sigmoid):
// - by quantile: detections below the q-quantile of the recent scores are "low" (any monotone
//   rescaling of the scores gives the same cut);
// - by range: below low + f x (high - low), where low and high are the 1st and 99th percentiles
//   of the recent scores (any affine rescaling gives the same cut; unlike the quantile it keeps
//   more of a sequence whose detections are mostly confident).
// - with a cap on the range: no range point lies above the c-quantile of the recent scores. A
//   fraction of the range suits scores whose true and false detections spread alike (a sigmoid, a
//   linear margin); where most scores pile up near a floor and the true ones spread over a long
//   upper tail (unbounded margins, un-squashed network outputs), 0.3 of the 1st..99th percentile
//   range lies far up the tail and marks most true detections low. The cap bounds the share marked
//   low by c whatever the shape, and where the range point lies below it (the shapes above) it
//   changes nothing.
// - engaged only on a floor-heavy shape: the cap applies only while its quantile lies below a
//   fraction g of the range (the default: the 0.4 quantile below 0.2 of the range, most scores
//   piled near a floor under a long upper tail). Where it sits higher, true and false detections
//   spread over the range alike, and a stream whose false detections merely outnumber its true
//   ones (its median low, but not at a floor) keeps the plain range split: capped, the split
//   would fall among the false ones.
// Causal: the cut for a frame depends on that frame and the ones before only, so `rtmot run` and
// `rtmot track` agree.
#include <cstdint>
#include <vector>

#include "tracker/box.hpp"
#include "tracker/recent_window.hpp"

namespace rtmot::tracker {

/// The Tracker's score window: about 100 frames of a MOT15 scene, enough for a stable quantile,
/// short enough to follow a scene that changes.
inline constexpr int kScoreWindow = 1024;

class ScoreCut {
 public:
  /// `quantile` and `range_fraction` in [0, 1); 0 disables that cut. `window`: how many recent
  /// scores are remembered. `track_range`: keep the window for range_point() even with both cuts
  /// off. `range_cap_quantile` in [0, 1): every range point is at most that quantile of the recent
  /// scores (0: no cap). `range_cap_below` in (0, 1]: the cap applies only while that quantile
  /// lies below low + range_cap_below x (high - low) (1: whenever it is lower than a range point).
  ScoreCut(double quantile, double range_fraction, int window, bool track_range = false,
           double range_cap_quantile = 0.0, double range_cap_below = 1.0);

  /// Adds the finite scores of `detections` to the window; returns the cut for this frame
  /// (the lowest float when disabled or nothing was seen). Allocates nothing.
  float observe(const std::vector<Detection>& detections);

  /// low + f x (high - low) of the scores seen up to the last observe(), at most the cap quantile
  /// (the lowest float before any, or when the window is off).
  float range_point(double fraction) const;

  void reset();

 private:
  void recompute();

  double quantile_;
  double range_fraction_;
  double range_cap_quantile_;
  double range_cap_below_;
  RecentWindow window_;
  float cut_;
  float low_;   // 1st percentile of the window at the last recompute
  float high_;  // 99th
  float cap_;   // the cap quantile (the highest float: none)
};

}  // namespace rtmot::tracker
