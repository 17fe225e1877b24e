#pragma once
// A MOTChallenge dataset held in memory for `rtmot study`: each sequence's ground truth and both
// detection inputs are read once, then every configuration is tracked and scored from memory.
#include <filesystem>
#include <string>
#include <vector>

#include "mot/metrics.hpp"
#include "mot/sequence_counts.hpp"
#include "motio/frame_detections.hpp"
#include "motio/mot_files.hpp"
#include "tracker/box.hpp"
#include "tracker/tracker_config.hpp"

namespace rtmot::mot {

/// Where a run's detections come from.
enum class StudyInput {
  detections,    // det/det.txt: the public detector
  ground_truth,  // gt/gt.txt without its ids: a perfect detector
};

std::string_view to_string(StudyInput input);

struct LoadedSequence {
  motio::SequenceInfo info;
  std::vector<motio::MotRow> gt_rows;
  motio::FrameDetections detections;     // det/det.txt
  motio::FrameDetections gt_detections;  // gt/gt.txt
};

/// Every sequence under `dataset` (a sequence folder or a folder of them). Throws InputError.
std::vector<LoadedSequence> load_study_dataset(const std::filesystem::path& dataset);

/// Tracks one sequence as `rtmot track` would (frames 1, 1 + interval, ...; time (frame - 1) /
/// frame rate) and scores it on the kept frames with the `rtmot eval` scorer.
SequenceCounts track_and_count(const LoadedSequence& sequence, StudyInput input,
                               const tracker::TrackerConfig& config, int interval);

/// All sequences pooled, as the OVERALL line of `rtmot eval`.
Metrics track_and_score(const std::vector<LoadedSequence>& dataset, StudyInput input,
                        const tracker::TrackerConfig& config, int interval);

}  // namespace rtmot::mot
