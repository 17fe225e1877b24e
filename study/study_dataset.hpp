#pragma once
// A MOTChallenge dataset held in memory for `rtmot study`: each sequence's ground truth and both
// detection inputs are read once, then every configuration is tracked and scored from memory.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "mot/metrics.hpp"
#include "mot/sequence_counts.hpp"
#include "motio/frame_detections.hpp"
#include "motio/mot_files.hpp"
#include "study/study_knobs.hpp"
#include "tracker/box.hpp"
#include "tracker/tracker_config.hpp"

namespace rtmot::study {

/// Where a run's detections come from.
struct StudyInput {
  enum class Kind {
    detections,    // det/det.txt: the public detector
    ground_truth,  // gt/gt.txt without its ids: a perfect detector
    synthetic,     // the ground truth through synthetic_detectors()[synthetic]
  };
  Kind kind{Kind::detections};
  int synthetic{-1};

  static const StudyInput detections;
  static const StudyInput ground_truth;
  static StudyInput synthetic_detector(int index) { return {Kind::synthetic, index}; }
  friend bool operator==(const StudyInput& a, const StudyInput& b) {
    return a.kind == b.kind && a.synthetic == b.synthetic;
  }
  friend bool operator!=(const StudyInput& a, const StudyInput& b) { return !(a == b); }
};
inline const StudyInput StudyInput::detections{StudyInput::Kind::detections, -1};
inline const StudyInput StudyInput::ground_truth{StudyInput::Kind::ground_truth, -1};

/// "det", "gt" or the synthetic detector's name: file-name safe.
std::string_view to_string(StudyInput input);
/// "det/det.txt", "gt/gt.txt (perfect detector)", or the synthetic detector's recipe.
std::string input_title(StudyInput input);
/// The synthetic detectors choices are made on (not held back), in synthetic_detectors() order.
std::vector<StudyInput> synthetic_inputs();
/// The held-back synthetic detectors, in synthetic_detectors() order.
std::vector<StudyInput> held_back_inputs();
/// Whether `input` is one of held_back_inputs(): its scores belong in the held-out tables only.
bool is_held_back(const StudyInput& input);

struct LoadedSequence {
  motio::SequenceInfo info;
  std::vector<motio::MotRow> gt_rows;
  motio::FrameDetections detections;              // det/det.txt
  motio::FrameDetections gt_detections;           // gt/gt.txt
  std::vector<motio::FrameDetections> synthetic;  // [i]: synthetic_detectors()[i] from gt/gt.txt
};

/// Every sequence under `dataset` (a sequence folder or a folder of them). Throws InputError.
std::vector<LoadedSequence> load_study_dataset(const std::filesystem::path& dataset);

/// Tracks one sequence as `rtmot track` would (frames 1, 1 + interval, ...; time (frame - 1) /
/// frame rate) and scores it on the kept frames with the `rtmot eval` scorer.
mot::SequenceCounts track_and_count(const LoadedSequence& sequence, StudyInput input,
                                    const tracker::TrackerConfig& config, int interval,
                                    const StudyKnobs& knobs);

/// All sequences pooled, as the OVERALL line of `rtmot eval`.
mot::Metrics track_and_score(const std::vector<LoadedSequence>& dataset, StudyInput input,
                             const tracker::TrackerConfig& config, int interval,
                             const StudyKnobs& knobs);

}  // namespace rtmot::study
