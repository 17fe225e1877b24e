#include "outputs/listen_board.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <string>
#include <utility>

#include "events/event.hpp"

namespace rtmot::outputs {
namespace {

double seconds(std::int64_t ns) {
  return static_cast<double>(ns) / 1e9;
}

// Only a message newer than every other of its stream replaces the tracks drawn: a late one, a
// duplicate or another sender's (a clash) would draw the past or someone else's scene.
bool newest(messages::Arrival arrival) {
  switch (arrival) {
    case messages::Arrival::first:
    case messages::Arrival::in_order:
    case messages::Arrival::after_gap:
    case messages::Arrival::restart:
      return true;
    case messages::Arrival::late:
    case messages::Arrival::duplicate:
    case messages::Arrival::clash:
      return false;
  }
  return false;
}

}  // namespace

ListenBoard::ListenBoard(messages::ClassLabelFn labels, std::int64_t started_ns)
    : labels_(std::move(labels)), started_ns_(started_ns) {}

ListenBoard::Stream& ListenBoard::stream(std::uint32_t id, std::int64_t now_ns) {
  auto found = streams_.find(id);
  if (found != streams_.end()) return found->second;
  if (streams_.size() >= kMaxStreams) {
    const auto oldest =
        std::min_element(streams_.begin(), streams_.end(), [](const auto& a, const auto& b) {
          return a.second.last_heard_ns < b.second.last_heard_ns;
        });
    streams_.erase(oldest);
    ++evicted_;
  }
  Stream& made = streams_[id];
  made.first_heard_ns = now_ns;
  made.window_start_ns = now_ns;
  return made;
}

void ListenBoard::record(const messages::DecodedMessage& message, messages::Arrival arrival,
                         const messages::StreamStats& stats, std::int64_t received_ns) {
  const messages::FrameResult& frame = message.frame;
  const std::lock_guard<std::mutex> lock(mutex_);
  ++received_;
  Stream& shown = stream(frame.stream_id, received_ns);
  shown.last_heard_ns = received_ns;
  ++shown.window_messages;
  if (received_ns - shown.window_start_ns >= 1'000'000'000) {
    shown.rate =
        static_cast<double>(shown.window_messages) / seconds(received_ns - shown.window_start_ns);
    shown.window_start_ns = received_ns;
    shown.window_messages = 0;
  }
  if (newest(arrival)) {
    shown.run_id = frame.run_id;
    shown.sequence = frame.sequence;
    shown.frame_number = frame.frame_number;
    shown.source_outage = frame.source_outage;
    shown.ended = frame.end_of_stream;
    // The end of a stream carries no tracks: its last frame's stay drawn, marked ended.
    if (!frame.end_of_stream) shown.tracks.assign(frame.tracks.begin(), frame.tracks.end());
    if (frame.frame_width != 0 && frame.frame_height != 0) {
      shown.frame_width = frame.frame_width;
      shown.frame_height = frame.frame_height;
    }
  }
  const auto& sequences = stats.sequences;
  shown.received = stats.messages;
  shown.lost = sequences.lost();
  shown.reordered = sequences.reordered();
  shown.duplicated = sequences.duplicated();
  shown.restarts = sequences.restarts();
  shown.clashes = sequences.clashes();
  shown.truncated = stats.truncated;
  shown.sender_skipped = stats.last_frames_dropped;
  shown.latency_mean_ms = stats.latency_mean_ns() / 1e6;
  if (!frame.events.empty()) shown.events = stats.events;  // rare: a copy per message with events
}

void ListenBoard::set_corrupt(std::uint64_t corrupt) {
  const std::lock_guard<std::mutex> lock(mutex_);
  corrupt_ = corrupt;
}

nlohmann::json ListenBoard::to_json(std::int64_t now_ns) const {
  std::map<std::uint32_t, Stream> streams;
  nlohmann::json out;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    streams = streams_;
    out["received"] = received_;
    out["corrupt"] = corrupt_;
    out["streams_evicted"] = evicted_;
  }
  out["uptime_s"] = seconds(now_ns - started_ns_);
  nlohmann::json list = nlohmann::json::array();
  for (const auto& [id, s] : streams) {
    const std::int64_t age_ns = now_ns - s.last_heard_ns;
    const bool up = age_ns < kDownAfterNs && !s.ended;
    nlohmann::json tracks = nlohmann::json::array();
    for (const auto& track : s.tracks) {
      tracks.push_back({{"id", track.id},
                        {"class", track.class_id},
                        {"label", labels_ ? std::string(labels_(track.class_id)) : ""},
                        {"score", track.score},
                        {"x", track.box.x},
                        {"y", track.box.y},
                        {"w", track.box.w},
                        {"h", track.box.h}});
    }
    nlohmann::json events = nlohmann::json::array();
    for (const auto& [kind_and_index, count] : s.events.listed()) {
      events.push_back({{"kind", std::string(events::kEventKindNames.name(
                                     static_cast<events::EventKind>(kind_and_index.first)))},
                        {"index", kind_and_index.second},
                        {"count", count}});
    }
    list.push_back({{"stream", id},
                    {"run", s.run_id != 0 ? fmt::format("{:016x}", s.run_id) : ""},
                    {"width", s.frame_width},
                    {"height", s.frame_height},
                    {"up", up},
                    {"ended", s.ended},
                    {"source_outage", s.source_outage},
                    {"age_s", seconds(age_ns)},
                    {"heard_for_s", seconds(s.last_heard_ns - s.first_heard_ns)},
                    {"rate", age_ns < kDownAfterNs ? s.rate : 0.0},
                    {"sequence", s.sequence},
                    {"frame", s.frame_number},
                    {"received", s.received},
                    {"lost", s.lost},
                    {"reordered", s.reordered},
                    {"duplicated", s.duplicated},
                    {"restarts", s.restarts},
                    {"clashes", s.clashes},
                    {"truncated", s.truncated},
                    {"sender_skipped", s.sender_skipped},
                    {"latency_mean_ms", s.latency_mean_ms},
                    {"tracks", std::move(tracks)},
                    {"events", std::move(events)},
                    {"events_unlisted", s.events.unlisted()}});
  }
  out["streams"] = std::move(list);
  return out;
}

}  // namespace rtmot::outputs
