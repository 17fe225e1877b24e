#pragma once
// One source's live annotated picture for the web page (outputs/web_server.hpp, docs/web.md), as
// JPEG, made only while someone watches and at most kMaxPicturesPerSecond. The pipeline pays one
// relaxed atomic load per frame when nobody watches: the capture thread (a FrameTap) looks at the
// watcher count, the sink thread (observe()) at the encoder's request, and each returns. While
// someone watches, this object's own encoder thread asks for one frame at a time: the capture
// thread copies the next frame into a LatestSlot (pipeline/latest_slot.hpp, latest mode: it never
// waits) only when asked, and the sink thread copies the tracks of the first message at or after
// that frame into another. So the boxes are drawn on the picture they were found in (or, for a
// frame the detector skipped, on the frame just before the next one it processed), and a watcher
// costs the pipeline a few frame copies a second, not one per frame. The HTTP workers wait for the
// next JPEG under this object's mutex, which the pipeline's threads never take.
//
// Hand-off of the two requests (frame_wanted_, result_from_): the encoder sets each; the capture
// or sink thread clears it and then answers by publishing into its slot (a release); the encoder
// takes the answer (an acquire) before it sets the next request. So the clear happens before the
// next set, each flag has one writer at a time, and relaxed order on the flags is enough: the
// slots carry the data's ordering.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <limits>
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
  /// A watcher sees motion at this rate; more would cost the detector's cores (a JPEG of 768x576
  /// takes a few ms) for little a person notices (docs/web.md, "what it costs").
  static constexpr int kMaxPicturesPerSecond = 8;

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
  /// MJPEG clients now (a hint: see watchers_).
  int watchers() const { return watchers_.load(std::memory_order_relaxed); }
  /// Pictures encoded so far (0 while nobody ever watched: the tests' proof that nobody pays).
  std::uint64_t pictures_encoded() const { return encoded_.load(std::memory_order_relaxed); }

 private:
  void encode_loop();
  bool watched() const { return watchers_.load(std::memory_order_relaxed) > 0; }

  const std::uint32_t stream_id_;
  // A hint, not a hand-off: a frame copied just after the last watcher left, or missed just after
  // the first came, costs or loses one picture; relaxed is enough.
  std::atomic<int> watchers_{0};
  // The encoder's requests (see the header's comment for their order).
  static constexpr std::int64_t kNoRequest = std::numeric_limits<std::int64_t>::max();
  std::atomic<bool> frame_wanted_{false};
  std::atomic<std::int64_t> result_from_{kNoRequest};
  pipeline::LatestSlot<SideFrame> frames_{pipeline::SlotMode::latest};
  pipeline::LatestSlot<messages::FrameResult> results_{pipeline::SlotMode::latest};
  std::atomic<bool> stop_{false};
  std::atomic<std::uint64_t> encoded_{0};
  Overlay overlay_;  // encoder thread only
  std::mutex mutex_;
  std::condition_variable fresh_;
  std::condition_variable pace_;  // the encoder waits here between pictures; stop_ ends the wait
  Jpeg jpeg_;                     // guarded by mutex_
  std::uint64_t sequence_{0};     // guarded by mutex_
  std::thread encoder_;           // last: starts after every member above exists
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
