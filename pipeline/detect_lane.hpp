#pragma once
// One lane of the detect stage (pipeline/detect_stage.hpp): a Detector of its own and the batch it
// runs. With detector.in_flight = K the stage has K lanes; while one lane's batch runs (on the GPU:
// its own cv::dnn::Nets, hence its own CUDA stream and captured graph) the stage gathers the next
// batch into another lane, so the device never waits for the host's resize, decode and NMS.
//
// A lane is either inline (K = 1: submit() runs the batch at once, in the caller's thread, exactly
// the single-threaded stage of before) or threaded (K > 1: a worker thread runs it).
//
// Hand-off, lock-free on the hot path, between the stage's thread (the only one that fills and
// empties the batch) and the lane's worker (the only one that runs it): one atomic state word.
//   idle --submit() [stage, release]--> queued --worker [acquire ... release]--> done
//   done --release() [stage, after its acquire in done()]--> idle
// The stage writes the batch only while the lane is idle and reads the results only after done()
// returned true (acquire, pairing with the worker's release store of `done`): the worker's writes
// of the detections happen before the stage reads them. The worker reads the batch only after its
// acquire of `queued`, pairing with submit()'s release store: the stage's writes of the pictures
// happen before the worker reads them. release() may be relaxed: only the stage reads `idle`, and
// the worker does not touch the batch again until the next `queued`. A worker with nothing to do
// sleeps in its own WakeSignal; a finished batch wakes the stage through the signal it sleeps in
// (the same one the capture threads notify).
#include <atomic>
#include <cstdint>
#include <exception>
#include <memory>
#include <opencv2/core/mat.hpp>
#include <thread>
#include <vector>

#include "detector/detector.hpp"
#include "pipeline/frame_trail.hpp"
#include "pipeline/wake_signal.hpp"
#include "platform/thread.hpp"
#include "platform/video_source.hpp"
#include "tracker/box.hpp"

namespace rtmot::pipeline {

/// One frame taken from a source's slot into a lane: its picture was swapped out of the slot (no
/// copy; the slot gets back the picture buffer this entry held, which the capture thread reuses).
struct LaneFrame {
  std::size_t input{0};
  platform::FrameInfo info;
  bool outage{false};
  std::int64_t taken_ns{0};  // when the stage took it from the slot
  FrameTrail trail;          // the frames read before it (full-rate output): copied, 3 KB
  cv::Mat image;
};

/// What a lane runs: up to one frame per source. Sized once for every source; reused.
struct LaneBatch {
  std::vector<LaneFrame> frames;  // the first `count` are this batch's
  std::size_t count{0};
  // Filled by the lane: the pictures (outage ticks have none) and their detections, in order.
  std::vector<const cv::Mat*> pictures;
  std::vector<std::int64_t> numbers;
  std::vector<std::vector<tracker::Detection>> detections;  // per picture, reserved
  std::int64_t start_ns{0};  // the detector's call, when there were pictures
  std::int64_t end_ns{0};
  std::exception_ptr error;  // what the detector threw; the stage rethrows it in batch order
};

class DetectLane {
 public:
  /// `stage_signal`: where the stage sleeps (a finished batch notifies it).
  DetectLane(std::unique_ptr<detector::Detector> detector, std::size_t inputs,
             std::size_t max_detections, WakeSignal& stage_signal);
  ~DetectLane();
  DetectLane(const DetectLane&) = delete;
  DetectLane& operator=(const DetectLane&) = delete;

  /// Threaded lanes: starts the worker (named by `settings`). Inline lanes never call it.
  void start(const platform::ThreadSettings& settings);
  /// Stops and joins the worker (after the batch it runs, if any). Idempotent.
  void stop();

  // ---- the stage's thread ----
  bool idle() const { return state_.load(std::memory_order_relaxed) == idle_state; }
  /// Fill only while idle().
  LaneBatch& batch() { return batch_; }
  /// Runs the filled batch: now (inline) or on the worker.
  void submit();
  /// The submitted batch has finished (its detections or its error are readable).
  bool done() const { return state_.load(std::memory_order_acquire) == done_state; }
  /// The results were handed on: the lane may be filled again.
  void release() { state_.store(idle_state, std::memory_order_relaxed); }

  const detector::Detector& detector() const { return *detector_; }

 private:
  static constexpr int idle_state = 0;
  static constexpr int queued_state = 1;
  static constexpr int done_state = 2;

  void run_batch();  // in whichever thread runs the lane
  void work();       // the worker's loop

  std::unique_ptr<detector::Detector> detector_;
  LaneBatch batch_;
  WakeSignal& stage_signal_;
  std::atomic<int> state_{idle_state};
  std::atomic<bool> stopping_{false};
  WakeSignal work_;  // the worker sleeps here
  std::thread worker_;
};

}  // namespace rtmot::pipeline
