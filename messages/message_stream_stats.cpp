#include "messages/message_stream_stats.hpp"

#include <algorithm>
#include <numeric>

namespace rtmot::messages {
namespace {

// Serial-number arithmetic (RFC 1982): `a` is ahead of `b` when (a - b) mod 2^64 is below half the
// range.
constexpr std::uint64_t kHalfRange = std::uint64_t{1} << 63;

std::uint64_t ahead_by(std::uint64_t sequence, std::uint64_t reference) {
  const std::uint64_t difference = sequence - reference;  // modulo 2^64
  return difference < kHalfRange ? difference : 0;
}

}  // namespace

void SequenceAccounting::start_epoch(std::uint64_t sequence, std::int64_t pts_ns) {
  started_ = true;
  first_ = sequence;
  highest_ = sequence;
  pts_at_highest_ = pts_ns;
  unique_in_epoch_ = 1;
  seen_.reset();
  mark(sequence);
}

bool SequenceAccounting::continues_previous_epoch(std::uint64_t sequence) const {
  if (!has_previous_epoch_) return false;
  const std::uint64_t ahead = ahead_by(sequence, previous_highest_);
  return ahead > 0 && ahead <= window;
}

Arrival SequenceAccounting::clash() {
  ++clashes_;
  return Arrival::clash;
}

Arrival SequenceAccounting::restart(std::uint64_t sequence, std::int64_t pts_ns) {
  lost_before_restarts_ += current_lost();
  ++restarts_;
  has_previous_epoch_ = true;
  previous_highest_ = highest_;
  start_epoch(sequence, pts_ns);
  return Arrival::restart;
}

Arrival SequenceAccounting::record(std::uint64_t sequence, std::int64_t pts_ns,
                                   std::uint64_t run_id) {
  ++received_;
  if (!started_) {
    run_id_ = run_id;
    start_epoch(sequence, pts_ns);
    return Arrival::first;
  }
  if (run_id != 0 && run_id != run_id_) {
    if (previous_run_id_ != 0 && run_id == previous_run_id_) return clash();
    if (run_id_ != 0) {
      previous_run_id_ = run_id_;
      run_id_ = run_id;
      return restart(sequence, pts_ns);
    }
    run_id_ = run_id;  // the first message that carries one: the run was already this one
  }
  const std::uint64_t ahead = ahead_by(sequence, highest_);
  if (ahead > 0) {
    if (pts_ns < pts_at_highest_) return clash();
    // Far ahead of this epoch but right after the one before the restart: its sender is still on.
    if (ahead > window && continues_previous_epoch(sequence)) {
      previous_highest_ = sequence;
      return clash();
    }
    // Forget the slots of the sequences skipped over, so that they can arrive late and be counted
    // as reordered rather than as duplicates of what used the slot `window` sequences before.
    if (ahead >= window) {
      seen_.reset();
    } else {
      for (std::uint64_t s = highest_ + 1; s != sequence; ++s) seen_[s % window] = false;
    }
    highest_ = sequence;
    pts_at_highest_ = pts_ns;
    mark(sequence);
    ++unique_in_epoch_;
    return ahead == 1 ? Arrival::in_order : Arrival::after_gap;
  }
  const std::uint64_t behind = highest_ - sequence;  // modulo 2^64; 0 for the highest itself
  if (behind == 0) {
    if (pts_ns != pts_at_highest_) return clash();
    ++duplicated_;
    return Arrival::duplicate;
  }
  if (pts_ns > pts_at_highest_) return clash();
  if (behind > window) {
    if (continues_previous_epoch(sequence)) {
      previous_highest_ = sequence;
      return clash();
    }
    return restart(sequence, pts_ns);
  }
  const bool in_epoch = behind <= highest_ - first_;
  if (in_epoch && seen(sequence)) {
    ++duplicated_;
    return Arrival::duplicate;
  }
  if (!in_epoch) first_ = sequence;  // late arrival from before the first one we saw
  mark(sequence);
  ++unique_in_epoch_;
  ++reordered_;
  return Arrival::late;
}

void EventTally::add(std::uint8_t kind, std::uint16_t index) {
  const Pair pair{kind, index};
  const auto known = listed_.find(pair);
  if (known != listed_.end()) {
    ++known->second;
  } else if (listed_.size() < max_pairs) {
    listed_.emplace(pair, 1);
  } else {
    ++unlisted_;
  }
}

std::uint64_t EventTally::total() const {
  std::uint64_t sum = unlisted_;
  for (const auto& entry : listed_) sum += entry.second;
  return sum;
}

ListenerStats::ListenerStats(std::size_t max_streams)
    : max_streams_(std::max<std::size_t>(max_streams, 1)) {}

StreamStats& ListenerStats::stream(std::uint32_t id) {
  const auto known = recency_of_.find(id);
  if (known != recency_of_.end()) {
    recency_.splice(recency_.begin(), recency_, known->second);  // now the most recent
    return streams_[id];
  }
  if (streams_.size() >= max_streams_) {
    const std::uint32_t oldest = recency_.back();
    recency_.pop_back();
    recency_of_.erase(oldest);
    const auto evicted = streams_.find(oldest);
    evicted_messages_ += evicted->second.sequences.received();
    streams_.erase(evicted);
    ++evicted_streams_;
  }
  recency_.push_front(id);
  recency_of_[id] = recency_.begin();
  return streams_[id];
}

Arrival ListenerStats::record(const DecodedMessage& message) {
  const FrameResult& frame = message.frame;
  StreamStats& stream = this->stream(frame.stream_id);
  const Arrival arrival = stream.sequences.record(frame.sequence, frame.pts_ns, frame.run_id);
  if (arrival == Arrival::duplicate || arrival == Arrival::clash) return arrival;
  for (const auto& event : frame.events)
    stream.events.add(static_cast<std::uint8_t>(event.kind), event.index);
  const bool first = stream.messages == 0;
  ++stream.messages;
  const std::int64_t latency = message.latency_ns();
  stream.latency_min_ns = first ? latency : std::min(stream.latency_min_ns, latency);
  stream.latency_max_ns = first ? latency : std::max(stream.latency_max_ns, latency);
  stream.latency_sum_ns += static_cast<double>(latency);
  stream.tracks += frame.tracks.size();
  if (message.truncated()) ++stream.truncated;
  if (frame.predicted) ++stream.predicted;
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
  std::uint64_t total = evicted_messages_;
  for (const auto& entry : streams_) total += entry.second.sequences.received();
  return total;
}

}  // namespace rtmot::messages
