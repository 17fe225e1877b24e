#pragma once
// What a receiver of track messages can tell about each stream from sequence numbers alone: how
// many arrived, were lost, came late (reordered) or twice (duplicated), and how many were corrupt.
#include <array>
#include <bitset>
#include <cstdint>
#include <list>
#include <map>
#include <utility>

#include "messages/message_format.hpp"

namespace rtmot::messages {

enum class Arrival { first, in_order, after_gap, late, duplicate, restart, clash };

/// Sequence accounting of one stream. Invariant: lost = sequences in [first, highest] not received
/// (so a late arrival that fills a gap un-loses it; losses after the last arrival cannot be seen).
/// Sequences compare as serial numbers (RFC 1982): 2^64 - 1 is followed by 0, and no count wraps.
/// Duplicates are recognised within the last `window` sequences; a sequence more than `window`
/// below the highest one means the sender restarted (its sequence starts at 0 again).
/// A message no single sender could have sent is a clash, counted apart and otherwise ignored:
/// two senders use one stream id. One sender's pts rises with its sequence, so a message ahead
/// with an older pts, or behind with a newer one, or the highest sequence again with another pts,
/// is another sender's; so is one that continues the sequence of the epoch before a restart.
class SequenceAccounting {
 public:
  static constexpr std::uint64_t window = 4096;

  /// `pts_ns`: the message's presentation time (0 when the sender has none: no clash is seen).
  /// `run_id`: the sender's run (0 when the message carries none). A new run id is a restart
  /// whatever the sequence says (a board restarted within `window` messages looked like
  /// duplicates); the previous run's id coming back after it is a clash.
  Arrival record(std::uint64_t sequence, std::int64_t pts_ns = 0, std::uint64_t run_id = 0);

  std::uint64_t received() const { return received_; }  // every valid message, duplicates included
  std::uint64_t lost() const { return lost_before_restarts_ + current_lost(); }
  std::uint64_t reordered() const { return reordered_; }
  std::uint64_t duplicated() const { return duplicated_; }
  std::uint64_t restarts() const { return restarts_; }
  std::uint64_t clashes() const { return clashes_; }

 private:
  std::uint64_t current_lost() const {
    return started_ ? (highest_ - first_) - (unique_in_epoch_ - 1) : 0;
  }
  void start_epoch(std::uint64_t sequence, std::int64_t pts_ns);
  Arrival restart(std::uint64_t sequence, std::int64_t pts_ns);
  bool continues_previous_epoch(std::uint64_t sequence) const;
  bool seen(std::uint64_t sequence) const { return seen_[sequence % window]; }
  void mark(std::uint64_t sequence) { seen_[sequence % window] = true; }
  Arrival clash();

  bool started_{false};
  std::uint64_t first_{0};    // lowest sequence of this epoch
  std::uint64_t highest_{0};  // highest sequence of this epoch (inclusive: 2^64 - 1 is valid)
  std::int64_t pts_at_highest_{0};
  bool has_previous_epoch_{false};
  std::uint64_t run_id_{0};            // of this epoch (0: not carried)
  std::uint64_t previous_run_id_{0};   // of the epoch before the last restart
  std::uint64_t previous_highest_{0};  // of the epoch before the last restart
  std::uint64_t unique_in_epoch_{0};
  std::uint64_t lost_before_restarts_{0};
  std::uint64_t received_{0};
  std::uint64_t reordered_{0};
  std::uint64_t duplicated_{0};
  std::uint64_t restarts_{0};
  std::uint64_t clashes_{0};
  std::bitset<window> seen_;  // seen_[s % window] for s in the last `window` sequences of the epoch
};

/// Events received on one stream (docs/events.md), by kind and line/zone index. A message may
/// name any of 256 x 65536 (kind, index) pairs; a spoofed stream naming millions of them made a
/// line of the summary and a map node each. So at most `max_pairs` pairs are counted apart, the
/// first ones seen (a configuration's own lines and zones come long before): an event of a pair
/// first seen after that is counted in `unlisted()` only.
class EventTally {
 public:
  static constexpr std::size_t max_pairs = 256;
  using Pair = std::pair<std::uint8_t, std::uint16_t>;  // {kind, index}

  void add(std::uint8_t kind, std::uint16_t index);
  const std::map<Pair, std::uint64_t>& listed() const { return listed_; }
  std::uint64_t unlisted() const { return unlisted_; }  // events of pairs beyond max_pairs
  std::uint64_t total() const;                          // every event added

 private:
  std::map<Pair, std::uint64_t> listed_;
  std::uint64_t unlisted_{0};
};

struct StreamStats {
  SequenceAccounting sequences;
  std::uint64_t messages{0};   // received without duplicates: what the figures below cover
  std::uint64_t truncated{0};  // messages that carried fewer tracks than their frame had
  std::uint64_t predicted{0};  // full-rate output: skipped frames sent with predicted boxes
  std::uint64_t tracks{0};     // tracks received, over all messages
  std::int64_t latency_min_ns{0};
  std::int64_t latency_max_ns{0};
  double latency_sum_ns{0.0};
  std::uint32_t last_frames_dropped{0};  // the sender's own count of frames it could not process
  EventTally events;                     // events received, by kind and line/zone index (bounded)

  double latency_mean_ns() const {
    return messages > 0 ? latency_sum_ns / static_cast<double>(messages) : 0.0;
  }
};

/// Everything `rtmot listen` counts: per stream id, and corrupt messages (which name no stream we
/// could trust) by reason. At most `max_streams` streams are kept (each costs ~0.7 KB, and its
/// event tally at most EventTally::max_pairs map nodes, ~16 KB): a message
/// of a new stream beyond that evicts the stream heard from least recently, and the evictions are
/// counted, so spoofed stream ids cannot grow memory or the summary without bound.
class ListenerStats {
 public:
  static constexpr std::size_t default_max_streams = 1024;

  explicit ListenerStats(std::size_t max_streams = default_max_streams);

  Arrival record(const DecodedMessage& message);
  void record_corrupt(DecodeError reason);

  const std::map<std::uint32_t, StreamStats>& streams() const { return streams_; }
  std::uint64_t corrupt() const;
  std::uint64_t corrupt(DecodeError reason) const {
    return corrupt_[static_cast<std::size_t>(reason)];
  }
  std::uint64_t received() const;  // valid messages over all streams, evicted ones included
  std::uint64_t evicted_streams() const { return evicted_streams_; }
  std::uint64_t evicted_messages() const { return evicted_messages_; }

 private:
  StreamStats& stream(std::uint32_t id);

  std::size_t max_streams_;
  std::map<std::uint32_t, StreamStats> streams_;  // one node per stream, made at its first message
  std::list<std::uint32_t> recency_;              // stream ids, most recently heard first
  std::map<std::uint32_t, std::list<std::uint32_t>::iterator> recency_of_;
  std::uint64_t evicted_streams_{0};
  std::uint64_t evicted_messages_{0};  // received by streams that were evicted
  std::array<std::uint64_t, decode_error_count> corrupt_{};
};

}  // namespace rtmot::messages
