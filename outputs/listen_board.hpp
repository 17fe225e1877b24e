#pragma once
// What `rtmot listen --web-port` shows (docs/web.md, "At the ground station"): for each stream
// heard, the latest message's tracks and frame size, its loss statistics and event counts (as the
// listener's summary counts them: messages/message_stream_stats.hpp), its message rate and how
// long ago it was last heard, timed by the listener's own steady clock on reception (never the
// board's clocks: a board whose clock is wrong shows the same).
//
// Threads: the receive thread (the UDP loop, or libmosquitto's thread) calls record() once per
// message; the page's HTTP workers call to_json(). One mutex guards the streams. The receive
// thread holds it to copy one message's tracks and a few counters into its stream (and the
// stream's event tally when the message carries events); a worker holds it only to copy the
// streams out (at most kMaxStreams, each one message's tracks: microseconds) and builds the JSON
// after releasing it. So the receive thread never waits longer than one such copy, whatever the
// number of browsers. The listener is not the real-time pipeline: a short mutex is the simple
// choice here, where a lock-free hand-over would need a copy per message anyway.
#include <cstddef>
#include <cstdint>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <vector>

#include "messages/jsonl_sink.hpp"
#include "messages/message_format.hpp"
#include "messages/message_stream_stats.hpp"

namespace rtmot::outputs {

class ListenBoard {
 public:
  /// Streams shown at once: a new stream beyond this takes the place of the one heard from least
  /// recently (spoofed stream ids cannot grow the page without bound).
  static constexpr std::size_t kMaxStreams = 64;
  /// A stream not heard for this long is shown down (its rate 0).
  static constexpr std::int64_t kDownAfterNs = 3'000'000'000;

  /// `labels` names the class ids (the boards' model's labels; COCO's by default).
  ListenBoard(messages::ClassLabelFn labels, std::int64_t started_ns);

  /// One valid message, as ListenerStats::record() judged it (`arrival`), with its stream's counts
  /// after it (`stats`), received at `received_ns` (platform::steady_now_ns()).
  void record(const messages::DecodedMessage& message, messages::Arrival arrival,
              const messages::StreamStats& stats, std::int64_t received_ns);
  /// Messages that could not be read, over every stream (they name none that could be trusted).
  void set_corrupt(std::uint64_t corrupt);

  /// The page's JSON (GET /api/listen): ages and rates as of `now_ns` (the steady clock).
  nlohmann::json to_json(std::int64_t now_ns) const;

 private:
  struct Stream {
    std::uint64_t run_id{0};
    std::uint16_t frame_width{0};
    std::uint16_t frame_height{0};
    std::uint64_t sequence{0};
    std::int64_t frame_number{0};
    bool source_outage{false};
    bool ended{false};
    std::vector<tracker::TrackReport> tracks;  // the newest message's (not a late one's)
    std::uint64_t received{0};
    std::uint64_t lost{0};
    std::uint64_t reordered{0};
    std::uint64_t duplicated{0};
    std::uint64_t restarts{0};
    std::uint64_t clashes{0};
    std::uint64_t truncated{0};
    std::uint32_t sender_skipped{0};
    double latency_mean_ms{0.0};
    messages::EventTally events;
    std::int64_t first_heard_ns{0};
    std::int64_t last_heard_ns{0};
    // Messages per second over the last whole second of arrivals.
    std::int64_t window_start_ns{0};
    std::uint64_t window_messages{0};
    double rate{0.0};
  };
  Stream& stream(std::uint32_t id, std::int64_t now_ns);

  messages::ClassLabelFn labels_;
  std::int64_t started_ns_;
  mutable std::mutex mutex_;  // guards everything below
  std::map<std::uint32_t, Stream> streams_;
  std::uint64_t evicted_{0};
  std::uint64_t received_{0};
  std::uint64_t corrupt_{0};
};

}  // namespace rtmot::outputs
