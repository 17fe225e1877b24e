#pragma once
// Runs the tracker over a MOTChallenge sequence's detections: the library side of `rtmot track`,
// and the loop the study runs too.
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "motio/frame_detections.hpp"
#include "motio/mot_files.hpp"
#include "tracker/tracker.hpp"
#include "tracker/tracker_config.hpp"
#include "tracker/tracker_extension.hpp"

namespace rtmot::motio {

/// The tracker options a sequence supplies (its seqinfo.ini's frame rate and image size):
/// track_detections sets them, whatever the configuration said.
inline const std::vector<std::string_view> kSequenceSuppliedOptions{"frame_rate", "image_width",
                                                                    "image_height"};

struct TrackOptions {
  /// frame_rate and image size are taken from the sequence's seqinfo.ini.
  tracker::TrackerConfig config{tracker::TrackerConfig::sort_preset()};
  /// Relative to the sequence folder. A file named gt.txt is used as a perfect detector: its ids
  /// and its ignored rows (conf 0, non-pedestrian classes) are dropped.
  std::filesystem::path detections{"det/det.txt"};
  /// Process frames 1, 1 + interval, ... only, keeping their numbers and times. 1..kMaxFrame.
  int interval{1};
  /// When not empty: process exactly these frames (ascending, in 1..length), e.g. those a
  /// pipeline with a slow detector would process (common/simulated_clock.hpp); `interval` is
  /// then not used.
  std::vector<int> frames;
  /// Full-rate output (docs/full-rate.md): every frame between two processed ones also gets rows,
  /// each track the last update reported at its box predicted for that frame's time
  /// (Tracker::predict_reported_at; the tracker's state is not changed by it).
  bool predict_skipped{false};
  /// Which reported tracks get the predicted rows (tracker::kPredictedMinHits: the product's rule).
  int predict_min_hits{tracker::kPredictedMinHits};
  /// When set and true, the run stops before its next frame (TrackRun::stopped).
  const std::atomic<bool>* stop{nullptr};
  /// The study's rules (study/study_knobs.hpp) for the Tracker; empty in the product.
  tracker::TrackerExtensionFactory extension;
};

struct TrackRun {
  SequenceInfo info;
  std::vector<MotRow> tracks;  // one row per reported track and frame
  int frames_processed{0};
  std::vector<int> processed_frames;  // their numbers, ascending (motio/processed_frames.hpp)
  int frames_predicted{0};            // frames given predicted rows (TrackOptions::predict_skipped)
  std::int64_t update_ns{0};          // time spent inside Tracker::update only
  bool stopped{false};                // by TrackOptions::stop, before the sequence's end
  /// Frames with more detections than the tracker's max_detections (it used the first ones of
  /// each), and the most detections one frame had: the caller says so rather than cut silently.
  int frames_over_capacity{0};
  std::size_t most_detections{0};
};

/// Called after each processed frame with (frame, sequence length); for progress reports.
using ProgressCallback = std::function<void(int frame, int length)>;

TrackRun track_sequence(const std::filesystem::path& sequence_dir, const TrackOptions& options,
                        const ProgressCallback& progress = {});

/// The tracker over `detections` (options.detections is not read): frames 1, 1 + interval, ...
/// of `info`'s length (or options.frames), at time (frame - 1) / frame rate.
TrackRun track_detections(const FrameDetections& detections, const SequenceInfo& info,
                          const TrackOptions& options, const ProgressCallback& progress = {});

/// The detections a TrackOptions::detections file holds, by frame.
FrameDetections load_detections(const std::filesystem::path& file, const SequenceInfo& info);

}  // namespace rtmot::motio
