#include "messages/message_stream_stats.hpp"

#include <algorithm>
#include <numeric>

namespace rtmot::messages {

void SequenceAccounting::start_epoch(std::uint64_t sequence) {
  started_ = true;
  first_ = sequence;
  next_ = sequence + 1;
  unique_in_epoch_ = 1;
  seen_.reset();
  mark(sequence);
}

Arrival SequenceAccounting::record(std::uint64_t sequence) {
  ++received_;
  if (!started_) {
    start_epoch(sequence);
    return Arrival::first;
  }
  if (sequence >= next_) {
    // Forget the slots of the sequences skipped over, so that they can arrive late and be counted
    // as reordered rather than as duplicates of what used the slot `window` sequences before.
    const std::uint64_t skipped = sequence - next_;
    if (skipped + 1 >= window) {
      seen_.reset();
    } else {
      for (std::uint64_t s = next_; s < sequence; ++s) seen_[s % window] = false;
    }
    const Arrival arrival = skipped == 0 ? Arrival::in_order : Arrival::after_gap;
    next_ = sequence + 1;
    mark(sequence);
    ++unique_in_epoch_;
    return arrival;
  }
  if (next_ - sequence > window) {
    lost_before_restarts_ += current_lost();
    ++restarts_;
    start_epoch(sequence);
    return Arrival::restart;
  }
  if (sequence >= first_ && seen(sequence)) {
    ++duplicated_;
    return Arrival::duplicate;
  }
  if (sequence < first_) first_ = sequence;  // late arrival from before the first one we saw
  mark(sequence);
  ++unique_in_epoch_;
  ++reordered_;
  return Arrival::late;
}

Arrival ListenerStats::record(const DecodedMessage& message) {
  const FrameResult& frame = message.frame;
  StreamStats& stream = streams_[frame.stream_id];
  const Arrival arrival = stream.sequences.record(frame.sequence);
  if (arrival == Arrival::duplicate) return arrival;
  const bool first = stream.messages == 0;
  ++stream.messages;
  const std::int64_t latency = message.latency_ns();
  stream.latency_min_ns = first ? latency : std::min(stream.latency_min_ns, latency);
  stream.latency_max_ns = first ? latency : std::max(stream.latency_max_ns, latency);
  stream.latency_sum_ns += static_cast<double>(latency);
  stream.tracks += frame.tracks.size();
  if (message.truncated()) ++stream.truncated;
  stream.last_frames_dropped = std::max(stream.last_frames_dropped, frame.frames_dropped);
  return arrival;
}

void ListenerStats::record_corrupt(DecodeError reason) {
  ++corrupt_[static_cast<std::size_t>(reason)];
}

std::uint64_t ListenerStats::corrupt() const {
  return std::accumulate(corrupt_.begin(), corrupt_.end(), std::uint64_t{0});
}

std::uint64_t ListenerStats::received() const {
  std::uint64_t total = 0;
  for (const auto& entry : streams_) total += entry.second.sequences.received();
  return total;
}

}  // namespace rtmot::messages
