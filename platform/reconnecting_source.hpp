#pragma once
// A live source that survives outages: when the camera or stream it wraps fails, stalls or ends, it
// reopens it with capped exponential backoff. While disconnected, read() returns `error` promptly
// (reason "reconnecting: ...") so that the pipeline keeps running: it can still send messages with
// coasting tracks. Files (sources that are not live) are passed through unchanged: their end is
// real.
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "platform/video_source.hpp"

namespace rtmot::platform {

struct ReconnectPolicy {
  std::chrono::milliseconds initial_delay{100};  // wait before the first reopen after an outage
  std::chrono::milliseconds max_delay{5000};     // the doubling delay is capped here
  /// Longest a read() blocks while disconnected before returning `error` (the caller's tick).
  std::chrono::milliseconds poll_interval{100};
  /// Cold start: a source that cannot be opened at start-up is retried with the same backoff as an
  /// outage (a camera that boots slower than the board) instead of failing the construction.
  bool retry_first_open{false};
};

struct ReconnectStats {
  std::int64_t outages{0};          // times a connected source failed, stalled or ended
  std::int64_t reconnects{0};       // successful reopens
  std::int64_t failed_attempts{0};  // reopens that threw
  std::int64_t frames_lost{0};      // estimated from the outage time and the nominal fps
};

/// Time as the backoff sees it: a steady clock and a sleep, replaceable in tests.
struct ReconnectClock {
  std::function<std::int64_t()> now_ns;
  std::function<void(std::int64_t)> sleep_ns;
  static ReconnectClock steady();
};

class ReconnectingSource final : public VideoSource {
 public:
  using Factory = std::function<std::unique_ptr<VideoSource>()>;

  /// Opens the first source now. If that fails, the factory's InputError propagates, unless
  /// policy.retry_first_open: then the source starts disconnected (an outage from the start:
  /// read() returns `error`, reconnecting() is true) and `expected` stands for its info (uri, live,
  /// the configured fps and size, 0 where unknown) until the source opens.
  explicit ReconnectingSource(Factory factory, ReconnectPolicy policy = {},
                              ReconnectClock clock = ReconnectClock::steady(),
                              SourceInfo expected = {});

  /// Frame numbers continue across reconnects, with a gap for the frames the outage cost (estimated
  /// from the nominal fps), and pts_ns keeps increasing: downstream never sees time run backwards.
  ReadStatus read(cv::Mat& bgr, FrameInfo& info) override;
  /// The first source's info (uri, live, fps, size); a reopened source may differ in size only.
  const SourceInfo& info() const override { return info_; }
  std::string last_error() const override { return last_error_; }

  /// True between an outage and the next successful reopen.
  bool disconnected() const { return source_ == nullptr; }
  bool reconnecting() const override { return disconnected(); }
  const ReconnectStats& stats() const { return stats_; }
  /// The delay before the next reopen attempt (for logs and tests).
  std::chrono::milliseconds current_delay() const { return delay_; }

 private:
  ReadStatus read_connected(cv::Mat& bgr, FrameInfo& info);
  ReadStatus wait_or_reopen(cv::Mat& bgr, FrameInfo& info);
  void begin_outage(const std::string& reason);

  Factory factory_;
  const ReconnectPolicy policy_;
  const ReconnectClock clock_;
  std::unique_ptr<VideoSource> source_;
  SourceInfo info_;
  std::string last_error_;
  ReconnectStats stats_;

  std::chrono::milliseconds delay_;
  std::int64_t next_attempt_ns_{0};
  std::int64_t outage_start_ns_{0};
  bool frame_since_reopen_{true};
  // Mapping of the current source's numbering onto the continuous one we hand out.
  std::int64_t frame_offset_{0};
  std::int64_t pts_offset_ns_{0};
  std::int64_t last_frame_number_{0};
  std::int64_t last_pts_ns_{0};
};

}  // namespace rtmot::platform
