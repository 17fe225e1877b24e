#include "pipeline/detect_stage.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

#include "platform/clock.hpp"

namespace rtmot::pipeline {
namespace {

using platform::steady_now_ns;

}  // namespace

DetectStage::DetectStage(std::vector<std::unique_ptr<detector::Detector>> detectors,
                         std::vector<LatestFrameSlot*> inputs, WakeSignal& frames_ready,
                         const DetectOptions& options)
    : inputs_(std::move(inputs)),
      frames_ready_(frames_ready),
      options_(options),
      // A whole batch fits, so the stage never waits for the tracker in the middle of one.
      output_(std::max(options.queue_capacity, inputs_.size()),
              [&](DetectedFrame& item) { item.detections.reserve(options.max_detections); }) {
  if (detectors.empty()) throw std::invalid_argument("the detect stage needs a detector");
  for (auto& detector : detectors) {
    if (!detector) throw std::invalid_argument("the detect stage got no detector");
    lanes_.push_back(std::make_unique<DetectLane>(std::move(detector), inputs_.size(),
                                                  options.max_detections, frames_ready_));
  }
}

DetectStage::~DetectStage() = default;

void DetectStage::wake_all() {
  frames_ready_.notify();
  output_.wake_all();
}

bool DetectStage::any_fresh() const {
  return std::any_of(inputs_.begin(), inputs_.end(), [](auto* slot) { return slot->fresh(); });
}

bool DetectStage::every_open_fresh() const {
  return std::all_of(inputs_.begin(), inputs_.end(),
                     [](auto* slot) { return slot->fresh() || slot->closed(); });
}

// closed() first: its acquire makes every publish before the close visible to fresh().
bool DetectStage::all_drained() const {
  return std::all_of(inputs_.begin(), inputs_.end(),
                     [](auto* slot) { return slot->closed() && !slot->fresh(); });
}

bool DetectStage::ready_to_take() {
  if (in_flight_ == lanes_.size() || !any_fresh()) return false;
  if (inputs_.size() == 1 || options_.batch_wait.count() <= 0 || every_open_fresh()) return true;
  const auto now = std::chrono::steady_clock::now();
  if (!gathering_) {
    gathering_ = true;
    gather_until_ = now + options_.batch_wait;
    return false;
  }
  return now >= gather_until_;
}

// Takes the newest frame of every source that has one into the next free lane and runs it there.
void DetectStage::take_batch() {
  DetectLane& lane = *lanes_[(oldest_ + in_flight_) % lanes_.size()];
  LaneBatch& batch = lane.batch();
  batch.count = 0;
  for (std::size_t i = 0; i < inputs_.size(); ++i) {
    if (!inputs_[i]->try_take()) continue;
    FrameSlotItem& item = inputs_[i]->front();
    LaneFrame& frame = batch.frames[batch.count++];
    frame.input = i;
    frame.info = item.info;
    frame.outage = item.outage;
    frame.trail = item.trail;
    frame.taken_ns = steady_now_ns();
    // The picture moves into the lane; the slot keeps the buffer the lane held (same size in
    // steady state), for the capture thread to decode into again.
    std::swap(frame.image, item.image);
  }
  gathering_ = false;
  if (batch.count == 0) return;
  lane.submit();
  ++in_flight_;
}

// Queues one DetectedFrame per frame of the lane's batch, in input order (outage ticks have no
// detections: the tracker will coast). Rethrows the lane's error.
bool DetectStage::hand_on(DetectLane& lane, const std::atomic<bool>& abort) {
  LaneBatch& batch = lane.batch();
  if (batch.error) std::rethrow_exception(batch.error);
  if (!batch.pictures.empty()) {
    counts_.frames += static_cast<std::int64_t>(batch.pictures.size());
    ++counts_.batches;
    busy_.add(batch.start_ns, batch.end_ns);
    counts_.busy_ns = busy_.busy_ns();
  }
  std::size_t picture = 0;
  // Read once per batch: all its boxes are cut by one value (pipeline/score_cut.hpp). At the
  // detector's own cut nothing is removed: its boxes are what it gives (a tile's box may be kept
  // under the whole frame's cut by detector.tile_threshold).
  const float cut = options_.score_cut != nullptr ? options_.score_cut->get() : 0.F;
  const bool cutting = options_.score_cut != nullptr && cut > options_.score_cut->floor();
  for (std::size_t i = 0; i < batch.count; ++i) {
    LaneFrame& frame = batch.frames[i];
    DetectedFrame* out = output_.claim(abort);
    if (out == nullptr) return false;
    if (frame.outage) {
      out->detections.clear();
    } else {
      const auto& boxes = batch.detections[picture++];
      out->detections.clear();  // then within the reserved capacity
      for (const auto& box : boxes) {
        if (!cutting || box.score >= cut) out->detections.push_back(box);
      }
    }
    out->input = frame.input;
    out->outage = frame.outage;
    out->times = messages::FrameTimes{};
    out->times.captured_ns = frame.info.capture_ns;
    out->times.detect_start_ns = frame.taken_ns;
    out->times.detected_ns = batch.end_ns;
    out->info = frame.info;
    // Full-rate output: the frames read before this one (frame_trail.hpp).
    out->trail = frame.trail;
    if (options_.keep_images) std::swap(out->image, frame.image);
    output_.publish();
  }
  return true;
}

void DetectStage::run(const std::atomic<bool>& abort) {
  // Every lane's worker is stopped and joined on every way out of here, an error included.
  struct StopLanes {
    std::vector<std::unique_ptr<DetectLane>>& lanes;
    ~StopLanes() {
      for (auto& lane : lanes) lane->stop();
    }
  } stop_lanes{lanes_};
  if (lanes_.size() > 1) {
    for (std::size_t i = 0; i < lanes_.size(); ++i) {
      lanes_[i]->start({"rtmot-lane-" + std::to_string(i + 1), -1, options_.lane_fifo_priority});
    }
  }
  const auto aborted = [&] { return abort.load(std::memory_order_relaxed); };
  const std::size_t k = lanes_.size();
  for (;;) {
    while (oldest_done()) {
      DetectLane& lane = *lanes_[oldest_];
      const bool handed_on = hand_on(lane, abort);
      lane.release();
      oldest_ = (oldest_ + 1) % k;
      --in_flight_;
      if (!handed_on) return;
    }
    if (aborted()) return;
    if (ready_to_take()) {
      take_batch();
      continue;
    }
    if (in_flight_ == 0 && all_drained()) return;
    // Sleep until a frame comes (a lane is free), the oldest batch is done, or the gather window
    // ends. The capture threads and the lanes' workers all notify frames_ready_.
    const bool lane_free = in_flight_ < k;
    const bool gathering = gathering_;
    frames_ready_.wait_until_deadline(
        [&] {
          return aborted() || oldest_done() ||
                 (lane_free && (gathering ? every_open_fresh() : any_fresh())) ||
                 (in_flight_ == 0 && all_drained());
        },
        gathering && lane_free ? gather_until_ : std::chrono::steady_clock::time_point::max());
  }
}

}  // namespace rtmot::pipeline
