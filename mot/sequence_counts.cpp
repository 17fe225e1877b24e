#include "mot/sequence_counts.hpp"

namespace rtmot::mot {

SequenceCounts& operator+=(SequenceCounts& total, const SequenceCounts& more) {
  ClearCounts& c = total.clear;
  const ClearCounts& m = more.clear;
  c.gt_detections += m.gt_detections;
  c.true_positives += m.true_positives;
  c.false_positives += m.false_positives;
  c.false_negatives += m.false_negatives;
  c.id_switches += m.id_switches;
  c.fragmentations += m.fragmentations;
  c.gt_tracks += m.gt_tracks;
  c.mostly_tracked += m.mostly_tracked;
  c.partly_tracked += m.partly_tracked;
  c.mostly_lost += m.mostly_lost;
  c.frames += m.frames;
  c.iou_sum += m.iou_sum;

  total.identity.true_positives += more.identity.true_positives;
  total.identity.false_positives += more.identity.false_positives;
  total.identity.false_negatives += more.identity.false_negatives;

  for (int a = 0; a < kHotaAlphaCount; ++a) {
    total.hota.true_positives[a] += more.hota.true_positives[a];
    total.hota.false_negatives[a] += more.hota.false_negatives[a];
    total.hota.false_positives[a] += more.hota.false_positives[a];
    total.hota.association_sum[a] += more.hota.association_sum[a];
    total.hota.localization_sum[a] += more.hota.localization_sum[a];
  }
  return total;
}

}  // namespace rtmot::mot
