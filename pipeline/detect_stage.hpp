#pragma once
// The detect stage (thread rtmot-detect, one for all sources): takes the newest frame of every
// source that has one and runs them through the Detector as one batch, then hands each frame's
// detections to the track stage. With one source this is "take the newest frame, detect it".
//
// Batching: the stage sleeps until any source publishes; then, while some source still open has no
// new frame, it waits for it at most `batch_wait` (then runs without it: a slow or dead camera
// never holds the others back longer than that). Batch size is 1..N as frames arrive; the detector
// splits batches larger than its max_batch() itself.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <vector>

#include "detector/detector.hpp"
#include "pipeline/latest_frame_slot.hpp"
#include "pipeline/spsc_queue.hpp"
#include "pipeline/stage_items.hpp"

namespace rtmot::pipeline {

struct DetectOptions {
  bool keep_images{false};  // hand the image on (the annotated video)
  std::size_t queue_capacity{4};
  std::size_t max_detections{100};  // reserved per queued frame
  std::chrono::microseconds batch_wait{5000};
};

/// What the detect thread counted; read after it ended.
struct DetectCounts {
  std::int64_t frames{0};   // frames run through the detector (not outage ticks)
  std::int64_t batches{0};  // detector calls (batches)
  std::int64_t busy_ns{0};  // time inside the detector
};

class DetectStage {
 public:
  /// `inputs` publish into slots whose consumer signal is `frames_ready`.
  DetectStage(std::unique_ptr<detector::Detector> detector, std::vector<LatestFrameSlot*> inputs,
              WakeSignal& frames_ready, const DetectOptions& options);

  void run(const std::atomic<bool>& abort);
  /// Always called after run(): no more frames.
  void finish() { output_.close(); }
  /// Wakes the thread and the hand-offs it sleeps in (abort).
  void wake_all();

  SpscQueue<DetectedFrame>& output() { return output_; }
  const detector::Detector& detector() const { return *detector_; }
  DetectCounts counts() const { return counts_; }

 private:
  bool wait_for_frames(const std::atomic<bool>& abort);
  void take_batch();
  bool detect_and_hand_on(const std::atomic<bool>& abort);

  std::unique_ptr<detector::Detector> detector_;
  std::vector<LatestFrameSlot*> inputs_;
  WakeSignal& frames_ready_;
  const DetectOptions options_;
  SpscQueue<DetectedFrame> output_;

  // Scratch, sized once for every input: the frames of the current batch.
  std::vector<std::size_t> batch_;      // input indexes
  std::vector<std::int64_t> taken_ns_;  // per input
  std::vector<const cv::Mat*> images_;  // the batch's pictures, in the slots (no copy)
  std::vector<std::int64_t> numbers_;   // their frame numbers
  std::vector<std::vector<tracker::Detection>> detections_;  // per picture, reserved
  DetectCounts counts_;
};

}  // namespace rtmot::pipeline
