#pragma once
// The annotated video's copy of every source frame (pipeline/frame_tap.hpp): the capture thread
// copies each frame into a bounded lock-free SPSC queue (pipeline/spsc_queue.hpp); the sink thread
// takes them in order, so frames the detector skipped still reach the video. Slots keep their image
// buffers (a copy into a buffer of the same size allocates nothing). When the queue is full (the
// sink stage more than `capacity` frames behind the source) the frame is dropped and counted: the
// capture thread never waits for the video.
#include <atomic>
#include <cstdint>
#include <opencv2/core/mat.hpp>

#include "pipeline/frame_tap.hpp"
#include "pipeline/spsc_queue.hpp"

namespace rtmot::outputs {

struct SideFrame {
  cv::Mat image;
  platform::FrameInfo info;
};

class FrameSideChannel final : public pipeline::FrameTap {
 public:
  explicit FrameSideChannel(std::size_t capacity) : queue_(capacity, [](SideFrame&) {}) {}

  /// Capture thread.
  void on_frame(const cv::Mat& bgr, const platform::FrameInfo& info) override {
    SideFrame* slot = queue_.try_claim();
    if (slot == nullptr) {
      dropped_.fetch_add(1, std::memory_order_relaxed);
      return;
    }
    bgr.copyTo(slot->image);
    slot->info = info;
    queue_.publish();
  }

  /// Sink thread: the oldest frame not yet taken, or nullptr; pop() releases it.
  SideFrame* front() { return queue_.try_front(); }
  void pop() { queue_.pop(); }

  std::size_t capacity() const { return queue_.capacity(); }
  /// Frames the queue had no room for (statistic).
  std::uint64_t dropped() const { return dropped_.load(std::memory_order_relaxed); }

 private:
  pipeline::SpscQueue<SideFrame> queue_;
  std::atomic<std::uint64_t> dropped_{0};
};

}  // namespace rtmot::outputs
