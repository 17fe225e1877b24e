#pragma once
// The detect stage (thread rtmot-detect, one for all sources): takes the newest frame of every
// source that has one and runs them through a Detector as one batch, then hands each frame's
// detections to the track stage. With one source this is "take the newest frame, detect it".
//
// Batching: the stage sleeps until any source publishes; then, while some source still open has no
// new frame, it waits for it at most `batch_wait` (then runs without it: a slow or dead camera
// never holds the others back longer than that). Batch size is 1..N as frames arrive; the detector
// splits batches larger than its max_batch() itself.
//
// Batches in flight (detector.in_flight, docs/architecture.md): the stage owns K lanes
// (pipeline/detect_lane.hpp), each with its own Detector. K = 1: the one lane runs inline in this
// thread (gather, detect, hand on, gather...). K > 1: each lane has a worker thread
// (rtmot-lane-N); this thread gathers the next batch into a free lane while the others run, and
// hands the results on to the one output queue strictly in batch order (lanes are filled round
// robin, so the oldest batch in flight is always the next lane's). A frame's picture is swapped
// out of its source's slot into the lane (no copy), so the capture thread may publish the next
// frame while this one is still being detected. Per source, frames reach the tracker in order: a
// source's frame n+1 is in a later batch than its frame n.
//
// Accounting: `busy_ns` is the time during which at least one lane was inside its detector (the
// union of the lanes' intervals), so frames / busy_ns is the rate the detect stage sustains when it
// is never starved, for any K (docs/architecture.md). A lane's failure (the detector threw) is
// rethrown here when its batch's turn comes; the lanes are stopped and joined on every way out.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <vector>

#include "detector/detector.hpp"
#include "pipeline/busy_time.hpp"
#include "pipeline/detect_lane.hpp"
#include "pipeline/latest_frame_slot.hpp"
#include "pipeline/score_cut.hpp"
#include "pipeline/spsc_queue.hpp"
#include "pipeline/stage_items.hpp"

namespace rtmot::pipeline {

struct DetectOptions {
  bool keep_images{false};  // hand the image on (the annotated video)
  std::size_t queue_capacity{4};
  std::size_t max_detections{100};  // reserved per queued frame
  std::chrono::microseconds batch_wait{5000};
  int lane_fifo_priority{0};  // the lanes' workers (K > 1): SCHED_FIFO priority, 0 = normal
  /// The live score cut (pipeline/score_cut.hpp), applied to the detector's boxes; not owned, must
  /// outlive the stage; null: the detector's own cut alone.
  const ScoreCut* score_cut{nullptr};
};

/// What the detect thread counted; read after it ended.
struct DetectCounts {
  std::int64_t frames{0};   // frames run through the detector (not outage ticks)
  std::int64_t batches{0};  // detector calls (batches)
  std::int64_t busy_ns{0};  // time during which some lane was inside its detector
};

class DetectStage {
 public:
  /// `detectors`: one per lane (detector.in_flight), at least one, all alike. `inputs` publish into
  /// slots whose consumer signal is `frames_ready`.
  DetectStage(std::vector<std::unique_ptr<detector::Detector>> detectors,
              std::vector<LatestFrameSlot*> inputs, WakeSignal& frames_ready,
              const DetectOptions& options);
  ~DetectStage();

  void run(const std::atomic<bool>& abort);
  /// Always called after run(): no more frames.
  void finish() { output_.close(); }
  /// Wakes the thread and the hand-offs it sleeps in (abort).
  void wake_all();

  SpscQueue<DetectedFrame>& output() { return output_; }
  const detector::Detector& detector() const { return lanes_.front()->detector(); }
  std::size_t lanes() const { return lanes_.size(); }
  DetectCounts counts() const { return counts_; }

 private:
  bool any_fresh() const;
  bool every_open_fresh() const;
  bool all_drained() const;
  bool oldest_done() const { return in_flight_ > 0 && lanes_[oldest_]->done(); }
  /// A free lane exists and the gather window allows taking now.
  bool ready_to_take();
  void take_batch();
  bool hand_on(DetectLane& lane, const std::atomic<bool>& abort);

  std::vector<std::unique_ptr<DetectLane>> lanes_;
  std::vector<LatestFrameSlot*> inputs_;
  WakeSignal& frames_ready_;
  const DetectOptions options_;
  SpscQueue<DetectedFrame> output_;

  // This thread's own state: lanes_[oldest_] holds the oldest batch in flight, in_flight_ batches
  // are, lanes_[(oldest_ + in_flight_) % K] is filled next.
  std::size_t oldest_{0};
  std::size_t in_flight_{0};
  bool gathering_{false};  // some frame is fresh and the gather window runs until gather_until_
  std::chrono::steady_clock::time_point gather_until_;
  BusyTime busy_;  // the union of the lanes' busy intervals so far
  DetectCounts counts_;
};

}  // namespace rtmot::pipeline
