#include "pipeline/detect_lane.hpp"

#include <utility>

#include "platform/clock.hpp"

namespace rtmot::pipeline {

DetectLane::DetectLane(std::unique_ptr<detector::Detector> detector, std::size_t inputs,
                       std::size_t max_detections, WakeSignal& stage_signal)
    : detector_(std::move(detector)), stage_signal_(stage_signal) {
  batch_.frames.resize(inputs);
  batch_.pictures.reserve(inputs);
  batch_.numbers.reserve(inputs);
  batch_.detections.resize(inputs);
  for (auto& boxes : batch_.detections) boxes.reserve(max_detections);
}

DetectLane::~DetectLane() {
  stop();
}

void DetectLane::start(const platform::ThreadSettings& settings) {
  worker_ = std::thread([this, settings] {
    platform::configure_current_thread(settings);
    work();
  });
}

void DetectLane::stop() {
  if (!worker_.joinable()) return;
  // release: nothing to publish with it, but the worker's acquire load below pairs with it.
  stopping_.store(true, std::memory_order_release);
  work_.notify();
  worker_.join();
}

void DetectLane::submit() {
  if (!worker_.joinable()) {
    run_batch();
    // The same thread reads the results: relaxed would do; release keeps one rule for both kinds.
    state_.store(done_state, std::memory_order_release);
    return;
  }
  // release: the batch's frames (filled by this thread) happen before the worker reads them.
  state_.store(queued_state, std::memory_order_release);
  work_.notify();
}

void DetectLane::work() {
  for (;;) {
    // acquire on queued_state: pairs with submit(); on stopping_: with stop().
    work_.wait_until([&] {
      return state_.load(std::memory_order_acquire) == queued_state ||
             stopping_.load(std::memory_order_acquire);
    });
    if (state_.load(std::memory_order_acquire) != queued_state) return;  // stopping, no work
    run_batch();
    // release: the detections happen before the stage's acquire in done().
    state_.store(done_state, std::memory_order_release);
    stage_signal_.notify();
  }
}

void DetectLane::run_batch() {
  LaneBatch& batch = batch_;
  batch.pictures.clear();
  batch.numbers.clear();
  batch.error = nullptr;
  for (std::size_t i = 0; i < batch.count; ++i) {
    const LaneFrame& frame = batch.frames[i];
    if (frame.outage) continue;
    batch.pictures.push_back(&frame.image);
    batch.numbers.push_back(frame.info.frame_number);
  }
  batch.start_ns = batch.end_ns = platform::steady_now_ns();
  if (batch.pictures.empty()) return;
  try {
    // One call for the whole batch: the SSD runs up to max_batch() pictures per forward pass and
    // splits larger batches itself.
    detector_->detect_batch(batch.pictures.data(), batch.numbers.data(),
                            static_cast<int>(batch.pictures.size()), batch.detections);
  } catch (...) {
    // Handed to the stage, which rethrows it when this batch's turn comes (the run's error path);
    // an exception must not leave a worker thread.
    batch.error = std::current_exception();
  }
  batch.end_ns = platform::steady_now_ns();
}

}  // namespace rtmot::pipeline
