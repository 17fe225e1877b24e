#pragma once
// The SSD detector's defaults, defined once: SsdPostprocessConfig, SsdConfig and runner's
// DetectorConfig (whose settings table documents them, docs/config.md) all start from these.
#include <vector>

namespace rtmot::detector {

/// Scores below this are dropped before NMS, before the tracker sees anything.
constexpr float kDefaultScoreThreshold = 0.5F;
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
