#include "pipeline/detect_stage.hpp"

#include <algorithm>
#include <utility>

#include "platform/clock.hpp"

namespace rtmot::pipeline {
namespace {

using platform::steady_now_ns;

}  // namespace

DetectStage::DetectStage(std::unique_ptr<detector::Detector> detector,
                         std::vector<LatestFrameSlot*> inputs, WakeSignal& frames_ready,
                         const DetectOptions& options)
    : detector_(std::move(detector)),
      inputs_(std::move(inputs)),
      frames_ready_(frames_ready),
      options_(options),
      // A whole batch fits, so the stage never waits for the tracker in the middle of one.
      output_(std::max(options.queue_capacity, inputs_.size()),
              [&](DetectedFrame& item) { item.detections.reserve(options.max_detections); }) {
  const std::size_t n = inputs_.size();
  batch_.reserve(n);
  taken_ns_.assign(n, 0);
  images_.reserve(n);
  numbers_.reserve(n);
  detections_.resize(n);
  for (auto& boxes : detections_) boxes.reserve(options.max_detections);
}

void DetectStage::wake_all() {
  frames_ready_.notify();
  output_.wake_all();
}

// Sleeps until some input has a frame. False once every input is closed and drained, or on abort.
bool DetectStage::wait_for_frames(const std::atomic<bool>& abort) {
  const auto any_fresh = [&] {
    return std::any_of(inputs_.begin(), inputs_.end(), [](auto* slot) { return slot->fresh(); });
  };
  // closed() first: its acquire makes every publish before the close visible to fresh().
  const auto all_drained = [&] {
    return std::all_of(inputs_.begin(), inputs_.end(),
                       [](auto* slot) { return slot->closed() && !slot->fresh(); });
  };
  frames_ready_.wait_until(
      [&] { return abort.load(std::memory_order_relaxed) || any_fresh() || all_drained(); });
  if (abort.load(std::memory_order_relaxed) || !any_fresh()) return false;
  if (inputs_.size() > 1 && options_.batch_wait.count() > 0) {
    const auto every_open_fresh = [&] {
      return std::all_of(inputs_.begin(), inputs_.end(),
                         [](auto* slot) { return slot->fresh() || slot->closed(); });
    };
    frames_ready_.wait_until_deadline(
        [&] { return abort.load(std::memory_order_relaxed) || every_open_fresh(); },
        std::chrono::steady_clock::now() + options_.batch_wait);
  }
  return true;
}

void DetectStage::take_batch() {
  batch_.clear();
  for (std::size_t i = 0; i < inputs_.size(); ++i) {
    if (inputs_[i]->try_take()) {
      taken_ns_[i] = steady_now_ns();
      batch_.push_back(i);
    }
  }
}

// Runs the detector on the batch's pictures (outage ticks have none: the tracker will coast), then
// queues one DetectedFrame per taken frame, in input order.
bool DetectStage::detect_and_hand_on(const std::atomic<bool>& abort) {
  images_.clear();
  numbers_.clear();
  for (const std::size_t input : batch_) {
    const FrameSlotItem& frame = inputs_[input]->front();
    if (frame.outage) continue;
    images_.push_back(&frame.image);  // the slot's own buffer, untouched until our next take
    numbers_.push_back(frame.info.frame_number);
  }
  if (!images_.empty()) {
    const std::int64_t start_ns = steady_now_ns();
    // One call for the whole batch: the SSD runs up to max_batch() pictures per forward pass and
    // splits larger batches itself.
    detector_->detect_batch(images_.data(), numbers_.data(), static_cast<int>(images_.size()),
                            detections_);
    counts_.busy_ns += steady_now_ns() - start_ns;
    counts_.frames += static_cast<std::int64_t>(images_.size());
    ++counts_.batches;
  }
  const std::int64_t detected_ns = steady_now_ns();
  std::size_t picture = 0;
  for (const std::size_t input : batch_) {
    FrameSlotItem& frame = inputs_[input]->front();
    DetectedFrame* out = output_.claim(abort);
    if (out == nullptr) return false;
    if (frame.outage) {
      out->detections.clear();
    } else {
      const auto& boxes = detections_[picture++];
      out->detections.assign(boxes.begin(), boxes.end());  // within the reserved capacity
    }
    out->input = input;
    out->outage = frame.outage;
    out->times = messages::FrameTimes{};
    out->times.captured_ns = frame.info.capture_ns;
    out->times.detect_start_ns = taken_ns_[input];
    out->times.detected_ns = detected_ns;
    out->info = frame.info;
    out->trail = frame.trail;
    if (options_.keep_images) std::swap(out->image, frame.image);
    output_.publish();
  }
  return true;
}

void DetectStage::run(const std::atomic<bool>& abort) {
  while (wait_for_frames(abort)) {
    take_batch();
    if (!batch_.empty() && !detect_and_hand_on(abort)) return;
  }
}

}  // namespace rtmot::pipeline
