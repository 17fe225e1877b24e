#include "messages/jsonl_sink.hpp"

#include <chrono>
#include <cmath>
#include <ctime>
#include <iterator>

namespace rtmot::messages {
namespace {

// Formatted with fmt into a reused buffer rather than built as an nlohmann::json tree: the tree
// allocates a node per field, per frame, and this sink may run on the board next to the tracker.
// fmt's "{}" prints the shortest text that reads back as the same float. JSON has no NaN/Inf: null.
void append_number(float value, fmt::memory_buffer& out) {
  if (std::isfinite(value)) {
    fmt::format_to(std::back_inserter(out), "{}", value);
  } else {
    fmt::format_to(std::back_inserter(out), "null");
  }
}

// ISO 8601 UTC with milliseconds, e.g. 2026-11-23T12:47:01.123Z: what dashboards parse.
void append_utc(std::int64_t wall_ns, fmt::memory_buffer& out) {
  const std::time_t seconds = static_cast<std::time_t>(wall_ns / 1000000000);
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  fmt::format_to(std::back_inserter(out), "{:04}-{:02}-{:02}T{:02}:{:02}:{:02}.{:03}Z",
                 utc.tm_year + 1900, utc.tm_mon + 1, utc.tm_mday, utc.tm_hour, utc.tm_min,
                 utc.tm_sec, (wall_ns / 1000000) % 1000);
}

}  // namespace

std::int64_t wall_now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

void append_json_line(const FrameResult& frame, std::uint32_t total_track_count, bool truncated,
                      const JsonLineExtras& extras, fmt::memory_buffer& out) {
  auto to = std::back_inserter(out);
  fmt::format_to(to, R"({{"schema":{},"time":")", json_schema_version);
  append_utc(extras.wall_ns, out);
  fmt::format_to(
      to,
      R"(","wall_ns":{},"stream":{},"sequence":{},"frame":{},"pts_ns":{},"captured_ns":{},"latency_ns":{},)"
      R"("frames_dropped":{},"source_outage":{},"truncated":{},"total_tracks":{},"tracks":[)",
      extras.wall_ns, frame.stream_id, frame.sequence, frame.frame_number, frame.pts_ns,
      frame.times.captured_ns,
      static_cast<std::int64_t>(static_cast<std::uint64_t>(frame.times.sent_ns) -
                                static_cast<std::uint64_t>(frame.times.captured_ns)),
      frame.frames_dropped, frame.source_outage, truncated, total_track_count);
  bool first = true;
  for (const auto& track : frame.tracks) {
    fmt::format_to(to, R"({}{{"id":{},"class":{},)", first ? "" : ",", track.id, track.class_id);
    if (extras.labels != nullptr && *extras.labels) {
      // Label tables refuse quotes, backslashes, control characters and bytes that are not UTF-8
      // where they are read (detector/label_table.cpp): no JSON escaping needed.
      fmt::format_to(to, R"("label":"{}",)", (*extras.labels)(track.class_id));
    }
    fmt::format_to(to, R"("score":)");
    append_number(track.score, out);
    fmt::format_to(to, R"(,"x":)");
    append_number(track.box.x, out);
    fmt::format_to(to, R"(,"y":)");
    append_number(track.box.y, out);
    fmt::format_to(to, R"(,"w":)");
    append_number(track.box.w, out);
    fmt::format_to(to, R"(,"h":)");
    append_number(track.box.h, out);
    fmt::format_to(to, R"(,"hits":{},"age":{}}})", track.hits, track.age);
    first = false;
  }
  fmt::format_to(to, "]");
  // Added fields (schema 2 still: nothing changed meaning): the sender's run id, as 16 hex digits
  // because a u64 does not survive JavaScript's doubles, the frame's size, the frame's events and
  // the end of the stream.
  if (frame.run_id != 0) fmt::format_to(to, R"(,"run":"{:016x}")", frame.run_id);
  if (frame.frame_width != 0 && frame.frame_height != 0) {
    fmt::format_to(to, R"(,"width":{},"height":{})", frame.frame_width, frame.frame_height);
  }
  if (!frame.events.empty()) {
    fmt::format_to(to, R"(,"events":[)");
    first = true;
    for (const auto& event : frame.events) {
      fmt::format_to(to, R"({}{{"kind":"{}","index":{},"track":{},"class":{},"x":)",
                     first ? "" : ",", events::kEventKindNames.name(event.kind), event.index,
                     event.track_id, event.class_id);
      append_number(event.x, out);
      fmt::format_to(to, R"(,"y":)");
      append_number(event.y, out);
      fmt::format_to(to, R"(,"dwell_s":)");
      append_number(static_cast<float>(event.dwell_seconds), out);
      fmt::format_to(to, R"(,"lost":{}}})", event.lost);
      first = false;
    }
    fmt::format_to(to, "]");
  }
  if (frame.end_of_stream) fmt::format_to(to, R"(,"end_of_stream":true)");
  if (frame.predicted) fmt::format_to(to, R"(,"predicted":true)");
  if (frame.predicted && frame.observed) fmt::format_to(to, R"(,"observed":true)");
  fmt::format_to(to, "}}\n");
}

JsonlSink::JsonlSink(const std::filesystem::path& path, ClassLabelFn labels)
    : file_(path), labels_(labels) {}

void JsonlSink::write(const FrameResult& result) {
  write_line(result, static_cast<std::uint32_t>(result.tracks.size()), false);
}

void JsonlSink::write(const DecodedMessage& message) {
  write_line(message.frame, message.total_track_count, message.truncated());
}

void JsonlSink::write_line(const FrameResult& frame, std::uint32_t total_track_count,
                           bool truncated) {
  line_.clear();
  append_json_line(frame, total_track_count, truncated, JsonLineExtras{wall_now_ns(), &labels_},
                   line_);
  file_.write(line_.data(), line_.size());
}

}  // namespace rtmot::messages
