#pragma once
// What a receiver of track messages can tell about each stream from sequence numbers alone: how
// many arrived, were lost, came late (reordered) or twice (duplicated), and how many were corrupt.
#include <array>
#include <bitset>
#include <cstdint>
#include <map>

#include "messages/message_format.hpp"

namespace rtmot::messages {

enum class Arrival { first, in_order, after_gap, late, duplicate, restart };

/// Sequence accounting of one stream. Invariant: lost = sequences in [first, highest] not received
/// (so a late arrival that fills a gap un-loses it; losses after the last arrival cannot be seen).
/// Duplicates are recognised within the last `window` sequences; a sequence more than `window`
/// below the highest one means the sender restarted (its sequence starts at 0 again).
class SequenceAccounting {
 public:
  static constexpr std::uint64_t window = 4096;

  Arrival record(std::uint64_t sequence);

  std::uint64_t received() const { return received_; }  // every valid message, duplicates included
  std::uint64_t lost() const { return lost_before_restarts_ + current_lost(); }
  std::uint64_t reordered() const { return reordered_; }
  std::uint64_t duplicated() const { return duplicated_; }
  std::uint64_t restarts() const { return restarts_; }

 private:
  std::uint64_t current_lost() const { return started_ ? (next_ - first_) - unique_in_epoch_ : 0; }
  void start_epoch(std::uint64_t sequence);
  bool seen(std::uint64_t sequence) const { return seen_[sequence % window]; }
  void mark(std::uint64_t sequence) { seen_[sequence % window] = true; }

  bool started_{false};
  std::uint64_t first_{0};  // lowest sequence of this epoch
  std::uint64_t next_{0};   // highest sequence seen + 1
  std::uint64_t unique_in_epoch_{0};
  std::uint64_t lost_before_restarts_{0};
  std::uint64_t received_{0};
  std::uint64_t reordered_{0};
  std::uint64_t duplicated_{0};
  std::uint64_t restarts_{0};
  std::bitset<window> seen_;  // seen_[s % window] for s in [max(first, next - window), next)
};

struct StreamStats {
  SequenceAccounting sequences;
  std::uint64_t messages{0};   // received without duplicates: what the figures below cover
  std::uint64_t truncated{0};  // messages that carried fewer tracks than their frame had
  std::uint64_t tracks{0};     // tracks received, over all messages
  std::int64_t latency_min_ns{0};
  std::int64_t latency_max_ns{0};
  double latency_sum_ns{0.0};
  std::uint32_t last_frames_dropped{0};  // the sender's own count of frames it could not process

  double latency_mean_ns() const {
    return messages > 0 ? latency_sum_ns / static_cast<double>(messages) : 0.0;
  }
};

/// Everything `rtmot listen` counts: per stream id, and corrupt messages (which name no stream we
/// could trust) by reason.
class ListenerStats {
 public:
  Arrival record(const DecodedMessage& message);
  void record_corrupt(DecodeError reason);

  const std::map<std::uint32_t, StreamStats>& streams() const { return streams_; }
  std::uint64_t corrupt() const;
  std::uint64_t corrupt(DecodeError reason) const {
    return corrupt_[static_cast<std::size_t>(reason)];
  }
  std::uint64_t received() const;  // valid messages over all streams

 private:
  std::map<std::uint32_t, StreamStats> streams_;  // one node per stream, made at its first message
  std::array<std::uint64_t, decode_error_count> corrupt_{};
};

}  // namespace rtmot::messages
