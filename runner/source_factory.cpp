#include "runner/source_factory.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>

#include "common/input_error.hpp"
#include "platform/reconnecting_source.hpp"
#include "platform/video_uri.hpp"
#include "runner/sequence_clock_source.hpp"

namespace rtmot::runner {

std::unique_ptr<platform::VideoSource> open_source(const std::string& uri,
                                                   const platform::SourceOptions& options) {
  if (is_sequence_uri(uri)) return std::make_unique<SequenceClockSource>(uri);
  if (!platform::is_live(platform::parse_video_uri(uri))) {
    return platform::open_video_source(uri, options);
  }
  // A camera or stream: ride out outages by reopening it with capped exponential backoff. A camera
  // missing at start-up is the same outage (cold start: it may boot slower than the board): the
  // service starts, reports source_outage and tracks once it appears. A malformed URI failed
  // above, and files are not live: both fail at once. The first open uses the configured
  // timeouts; reopens use short ones, because the pipeline's outage ticks (and so the messages to
  // the ground station) pause while a reopen blocks.
  // A missing GStreamer plugin (csi:// without NVIDIA's nvarguscamerasrc) never appears: exit 5
  // now, as docs/sources.md says, not retried for ever as if the camera were late.
  platform::require_source_elements(uri);
  platform::SourceOptions reopen = options;
  reopen.open_timeout_ms = std::min(options.open_timeout_ms, 2000);
  reopen.read_timeout_ms = std::min(options.read_timeout_ms, 1000);
  bool first = true;
  platform::ReconnectPolicy policy;
  policy.retry_first_open = true;
  platform::SourceInfo expected;
  expected.uri = uri;
  expected.live = true;
  expected.fps = options.fps;
  expected.width = options.width;
  expected.height = options.height;
  auto source = std::make_unique<platform::ReconnectingSource>(
      [uri, options, reopen, first]() mutable {
        const platform::SourceOptions& use = first ? options : reopen;
        first = false;
        return platform::open_video_source(uri, use);
      },
      policy, platform::ReconnectClock::steady(), expected);
  if (source->disconnected()) {
    spdlog::warn("{}: {}; retrying with backoff (up to {} s apart) until it appears", uri,
                 source->last_error(),
                 std::chrono::duration_cast<std::chrono::seconds>(policy.max_delay).count());
  }
  return source;
}

std::string ignored_capture_request(const std::string& uri,
                                    const platform::SourceOptions& options) {
  if (options.width <= 0 && options.height <= 0 && options.fps <= 0.0) return "";
  if (!is_sequence_uri(uri)) {
    try {
      // A camera takes them; an RTSP stream (live) uses them until it first appears (cold start:
      // the tracker's rate and size, docs/sources.md).
      if (platform::is_live(platform::parse_video_uri(uri))) return "";
    } catch (const InputError&) {
      return "";  // reported when the source opens
    }
  }
  return uri +
         ": source.width/height/fps (--input-width/-height/-rate) choose a camera's capture "
         "mode (v4l2://, csi://); a recording plays at its own size and rate (file://PATH?fps=N "
         "re-times one whose header is wrong)";
}

}  // namespace rtmot::runner
