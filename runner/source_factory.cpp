#include "runner/source_factory.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>

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

}  // namespace rtmot::runner
