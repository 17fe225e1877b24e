#pragma once
// Fault injection for test:// sources: after N buffers, the source's streaming thread stops for M
// ms, exactly as a camera whose driver hangs. (Errors and end-of-stream are injected with
// GStreamer's own identity error-after and videotestsrc num-buffers.)
#include <gst/gst.h>

#include <condition_variable>
#include <cstdint>
#include <mutex>

namespace rtmot::platform {

class StallInjector {
 public:
  StallInjector(int stall_after_frames, int stall_ms)
      : stall_after_(stall_after_frames), stall_ms_(stall_ms) {}
  StallInjector(const StallInjector&) = delete;
  StallInjector& operator=(const StallInjector&) = delete;

  /// Watches buffers leaving `pad`. This object must outlive the pipeline's streaming.
  void attach(GstPad* pad);
  /// Ends a stall in progress (and any later one) so the pipeline can be stopped promptly.
  void cancel();

 private:
  static GstPadProbeReturn on_buffer(GstPad* pad, GstPadProbeInfo* info, gpointer self);
  void stall();

  const std::int64_t stall_after_;
  const int stall_ms_;
  std::int64_t buffers_seen_{0};  // touched only by the streaming thread
  std::mutex mutex_;
  std::condition_variable wake_;
  bool cancelled_{false};
};

}  // namespace rtmot::platform
