#include "mot/metrics.hpp"

#include <algorithm>
#include <cmath>

namespace rtmot::mot {

namespace {

double percent(double part, double whole) {
  return whole > 0.0 ? 100.0 * part / whole : 0.0;
}

}  // namespace

Metrics summarize(const SequenceCounts& counts) {
  Metrics m;
  const ClearCounts& c = counts.clear;
  const IdentityCounts& id = counts.identity;
  const auto tp = static_cast<double>(c.true_positives);
  const auto fp = static_cast<double>(c.false_positives);
  const auto fn = static_cast<double>(c.false_negatives);
  const auto gt = static_cast<double>(c.gt_detections);

  m.idp = percent(id.true_positives, id.true_positives + id.false_positives);
  m.idr = percent(id.true_positives, id.true_positives + id.false_negatives);
  m.idf1 = percent(2.0 * id.true_positives,
                   2.0 * id.true_positives + id.false_positives + id.false_negatives);

  m.recall = percent(tp, gt);
  m.precision = percent(tp, tp + fp);
  m.false_alarms_per_frame = c.frames > 0 ? fp / static_cast<double>(c.frames) : 0.0;
  m.gt_tracks = c.gt_tracks;
  m.mostly_tracked = c.mostly_tracked;
  m.partly_tracked = c.partly_tracked;
  m.mostly_lost = c.mostly_lost;
  m.false_positives = c.false_positives;
  m.false_negatives = c.false_negatives;
  m.id_switches = c.id_switches;
  m.fragmentations = c.fragmentations;
  const auto ids = static_cast<double>(c.id_switches);
  m.mota = gt > 0.0 ? 100.0 * (1.0 - (fn + fp + ids) / gt) : 0.0;
  m.motal = gt > 0.0 ? 100.0 * (1.0 - (fn + fp + std::log10(ids + 1.0)) / gt) : 0.0;
  m.motp = percent(c.iou_sum, tp);

  // HOTA and its parts: per alpha as TrackEval, then the mean over the 19 alphas.
  const HotaCounts& h = counts.hota;
  for (int a = 0; a < kHotaAlphaCount; ++a) {
    const double hota_tp = h.true_positives[a];
    const double det_a =
        hota_tp / std::max(1.0, hota_tp + h.false_negatives[a] + h.false_positives[a]);
    const double ass_a = h.association_sum[a] / std::max(1.0, hota_tp);
    const double loc_a = std::max(1e-10, h.localization_sum[a]) / std::max(1e-10, hota_tp);
    m.deta += det_a;
    m.assa += ass_a;
    m.loca += loc_a;
    m.hota += std::sqrt(det_a * ass_a);
  }
  m.deta *= 100.0 / kHotaAlphaCount;
  m.assa *= 100.0 / kHotaAlphaCount;
  m.loca *= 100.0 / kHotaAlphaCount;
  m.hota *= 100.0 / kHotaAlphaCount;
  return m;
}

}  // namespace rtmot::mot
