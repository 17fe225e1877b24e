#pragma once
// The SSD detector's defaults, defined once: SsdPostprocessConfig, SsdConfig and runner's
// DetectorConfig (whose settings table documents them, docs/config.md) all start from these.
#include <vector>

namespace rtmot::detector {

/// Scores below this are dropped before NMS, before the tracker sees anything. Not 0.5: the
/// tracker's second round exists for the low-score detections (a person half hidden continues its
/// track), and at 0.5 clearly visible people of the demo video are missed (their reference
/// detections score 0.41..0.46). 0.3 is the lowest score the model's reference detections
/// (../shared, every detection >= 0.3) show; on the SSD's synthetic score model the default
/// tracker gains 9.3 / 10.0 / 7.3 MOTA at intervals 1 / 5 / 10 over 0.5 (docs/study.md, "The
/// detector's own cut").
constexpr float kDefaultScoreThreshold = 0.3F;
/// Boxes of one class overlapping a better one by more than this IoU are dropped: what the model's
/// training pipeline (ssdlite_mobilenet_v2_coco) uses.
constexpr float kDefaultNmsIou = 0.6F;
/// Per class and in total, as the TF pipeline.
constexpr int kDefaultMaxDetections = 100;
/// COCO's "person".
constexpr int kPersonClassId = 1;

/// The classes a run keeps unless told otherwise: people.
inline std::vector<int> default_classes() {
  return {kPersonClassId};
}

}  // namespace rtmot::detector
