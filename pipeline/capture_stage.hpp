#pragma once
// The capture stage (thread rtmot-capture, one per source): reads the VideoSource, applies the
// playback mode, stamps captured_ns and publishes into its LatestFrameSlot; during a live source's
// outage it publishes ticks without a picture. Owns the source, the slot and the counters only it
// writes.
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

#include "pipeline/frame_tap.hpp"
#include "pipeline/latest_frame_slot.hpp"
#include "pipeline/outage_board.hpp"
#include "pipeline/playback_mode.hpp"
#include "platform/video_source.hpp"

namespace rtmot::pipeline {

struct CaptureOptions {
  PlaybackMode playback{PlaybackMode::realtime};  // live sources always play realtime
  double simulated_latency_ms{250.0};
  std::int64_t max_frames{0};  // 0 = no limit
};

/// What the capture thread counted; read after it ended (frames_captured also while running).
struct CaptureCounts {
  std::int64_t frames_captured{0};
  std::int64_t frames_lost{0};       // gaps in the source's frame numbers
  std::int64_t outages{0};           // times the live source went down
  std::int64_t first_capture_ns{0};  // the first published frame's captured_ns
  std::string source_error;          // why the source ended with an error; empty = it did not
};

class CaptureStage {
 public:
  /// `detector_signal`: where the detect stage sleeps waiting for any source (shared by all).
  CaptureStage(std::unique_ptr<platform::VideoSource> source, const CaptureOptions& options,
               WakeSignal* detector_signal);

  /// The thread's body: until the end of the stream, max_frames, `stop` or `abort`.
  void run(const std::atomic<bool>& stop, const std::atomic<bool>& abort);
  /// Always called after run(): no more frames.
  void finish() { slot_.close(); }

  LatestFrameSlot& slot() { return slot_; }
  /// Before run(): every real frame is shown to `tap` (nullptr: none).
  void set_tap(FrameTap* tap) { tap_ = tap; }
  /// Before run(): the outages of every source of the pipeline, for the all-down lines.
  void set_outage_board(OutageBoard* board) { board_ = board; }
  const platform::VideoSource& source() const { return *source_; }
  bool live() const { return live_; }
  PlaybackMode playback() const { return playback_; }
  std::int64_t frames_captured() const { return frames_captured_.load(std::memory_order_relaxed); }
  /// After the thread ended.
  CaptureCounts counts() const;

 private:
  enum class Next { frame, outage_tick, end };

  Next read_frame(FrameSlotItem& item, const std::atomic<bool>& stop,
                  const std::atomic<bool>& abort);
  Next outage_tick(FrameSlotItem& item);
  bool publish(FrameSlotItem& item, const std::atomic<bool>& abort);
  void pass(const FrameSlotItem& item);
  void run_simulated(const std::atomic<bool>& stop, const std::atomic<bool>& abort);
  static bool wait_for_pts(std::int64_t due_ns, const std::atomic<bool>& stop,
                           const std::atomic<bool>& abort);

  std::unique_ptr<platform::VideoSource> source_;
  const CaptureOptions options_;
  const bool live_;
  const PlaybackMode playback_;
  LatestFrameSlot slot_;

  // Written by the capture thread only; the sink's periodic log reads frames_captured_ (relaxed:
  // a statistic).
  std::atomic<std::int64_t> frames_captured_{0};
  std::int64_t frames_lost_{0};
  std::int64_t outages_{0};
  bool in_outage_{false};
  std::int64_t outage_since_ns_{0};     // when the current outage began
  std::int64_t next_still_down_ns_{0};  // when the next "still down" line is due
  std::int64_t last_number_{0};         // the last real frame's number
  std::int64_t last_pts_ns_{0};         // the last real frame's
  std::int64_t last_capture_ns_{0};     // the last real frame's
  std::int64_t first_capture_ns_{0};
  FrameTrail trail_;  // the real frames read so far (the last FrameTrail::kCapacity)
  std::string source_error_;
  FrameTap* tap_{nullptr};
  OutageBoard* board_{nullptr};
};

}  // namespace rtmot::pipeline
