#pragma once
// One source's live annotated picture for the web page (outputs/web_server.hpp, docs/web.md), as
// JPEG, made only while someone watches. The pipeline pays one relaxed atomic load per frame when
// nobody does: the capture thread (a FrameTap) and the sink thread (observe()) look at the watcher
// count and return. While someone watches, the capture thread copies the frame into a LatestSlot
// (pipeline/latest_slot.hpp, latest mode: it never waits, a frame not yet taken is replaced) and
// the sink thread copies the tracks into another; this object's own encoder thread takes the
// newest of each, draws the tracks (outputs/overlay.hpp) and encodes the JPEG. The HTTP workers
// wait for the next JPEG under this object's mutex, which the pipeline's threads never take.
//
// The tracks drawn are the last processed frame's on the newest captured picture: behind it by
// the capture-to-sent latency (tens of ms on a CPU), which a person watching does not see.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "messages/frame_result.hpp"
#include "outputs/frame_side_channel.hpp"
#include "outputs/overlay.hpp"
#include "pipeline/frame_tap.hpp"
#include "pipeline/latest_slot.hpp"

namespace rtmot::outputs {

using Jpeg = std::shared_ptr<const std::vector<unsigned char>>;

class LivePicture final : public pipeline::FrameTap {
 public:
  LivePicture(std::uint32_t stream_id, OverlayFlags flags, messages::ClassLabelFn labels);
  ~LivePicture() override;
  LivePicture(const LivePicture&) = delete;
  LivePicture& operator=(const LivePicture&) = delete;

  std::uint32_t stream_id() const { return stream_id_; }

  /// Capture thread: every source frame.
  void on_frame(const cv::Mat& bgr, const platform::FrameInfo& info) override;
  /// Sink thread: every message (only pictures of this stream matter).
  void observe(const messages::FrameResult& result);

  /// While one lives, pictures are made (an HTTP worker holds one per MJPEG client).
  class Watcher {
   public:
    explicit Watcher(LivePicture& picture) : picture_(picture) {
      picture_.watchers_.fetch_add(1, std::memory_order_relaxed);
    }
    ~Watcher() { picture_.watchers_.fetch_sub(1, std::memory_order_relaxed); }
    Watcher(const Watcher&) = delete;
    Watcher& operator=(const Watcher&) = delete;

   private:
    LivePicture& picture_;
  };

  /// Any thread: the first JPEG newer than `sequence` (updated to its number), or null if none came
  /// within `wait`.
  Jpeg next_jpeg(std::uint64_t& sequence, std::chrono::milliseconds wait);
  /// Pictures encoded so far (0 while nobody ever watched: the tests' proof that nobody pays).
  std::uint64_t pictures_encoded() const { return encoded_.load(std::memory_order_relaxed); }

 private:
  void encode_loop();
  bool watched() const { return watchers_.load(std::memory_order_relaxed) > 0; }

  const std::uint32_t stream_id_;
  // A hint, not a hand-off: a frame copied just after the last watcher left, or missed just after
  // the first came, costs or loses one picture; relaxed is enough.
  std::atomic<int> watchers_{0};
  pipeline::LatestSlot<SideFrame> frames_{pipeline::SlotMode::latest};
  pipeline::LatestSlot<messages::FrameResult> results_{pipeline::SlotMode::latest};
  std::atomic<bool> stop_{false};
  std::atomic<std::uint64_t> encoded_{0};
  Overlay overlay_;  // encoder thread only
  std::mutex mutex_;
  std::condition_variable fresh_;
  Jpeg jpeg_;                  // guarded by mutex_
  std::uint64_t sequence_{0};  // guarded by mutex_
  std::thread encoder_;        // last: starts after every member above exists
};

/// The sink that hands every message to each source's picture (on the sink thread).
class LivePictureSink final : public messages::TrackSink {
 public:
  explicit LivePictureSink(std::vector<LivePicture*> pictures) : pictures_(std::move(pictures)) {}
  void write(const messages::FrameResult& result) override {
    for (LivePicture* picture : pictures_) picture->observe(result);
  }
  void flush() override {}

 private:
  std::vector<LivePicture*> pictures_;
};

}  // namespace rtmot::outputs
