#include "runner/source_factory.hpp"

#include <algorithm>

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
  // A camera or stream: ride out outages by reopening it with capped exponential backoff. The
  // first open uses the configured timeouts (a camera missing at start-up is a configuration error
  // and propagates); reopens use short ones, because the pipeline's outage ticks (and so the
  // messages to the ground station) pause while a reopen blocks.
  platform::SourceOptions reopen = options;
  reopen.open_timeout_ms = std::min(options.open_timeout_ms, 2000);
  reopen.read_timeout_ms = std::min(options.read_timeout_ms, 1000);
  bool first = true;
  return std::make_unique<platform::ReconnectingSource>([uri, options, reopen, first]() mutable {
    const platform::SourceOptions& use = first ? options : reopen;
    first = false;
    return platform::open_video_source(uri, use);
  });
}

}  // namespace rtmot::runner
