#pragma once
// `rtmot study --detector-cut`: where the pipeline's detector should cut its own scores (issue 21).
// The SSD drops every detection scoring below its `score_threshold` before the tracker sees it;
// the second association round exists for exactly those low-score detections. synth-ssd, the
// SSD's score model among the synthetic detectors (sigmoid(z - 1) of a latent confidence, its own
// floor at z = -1, a score of 0.12), is tracked with every detection below each cut dropped first,
// as the pipeline would: dropping the detections scoring below c is the same detector with its
// floor raised to the latent of c.
#include <string>
#include <vector>

#include "mot/metrics.hpp"
#include "study/study_dataset.hpp"

namespace rtmot::study {

struct DetectorCutRow {
  float cut{0.F};          // detections scoring below it are dropped before the tracker
  double kept_share{0.0};  // of the detector's detections
  std::vector<mot::Metrics> by_interval;
};

struct DetectorCutTable {
  std::string preset;    // a tracker preset's name
  std::string detector;  // a synthetic detector's name
  std::vector<DetectorCutRow> rows;
};

/// 0.5 (the SSD's default before issue 21), 0.4, 0.3, 0.25, 0.2 and 0.15.
std::vector<float> default_detector_cuts();

/// Every preset on `detector` (a synthetic detector's name) with each cut, all sequences pooled.
std::vector<DetectorCutTable> run_detector_cut_sweep(const std::vector<LoadedSequence>& dataset,
                                                     const std::vector<std::string>& presets,
                                                     const std::string& detector,
                                                     const std::vector<float>& cuts,
                                                     const std::vector<int>& intervals);

/// One Markdown table: a row per preset and cut, MOTA / IDF1 per interval.
std::string format_detector_cut_markdown(const std::vector<DetectorCutTable>& tables,
                                         const std::vector<int>& intervals);

}  // namespace rtmot::study
