#include "messages/jsonl_sink.hpp"

#include <cmath>
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

}  // namespace

void append_json_line(const FrameResult& frame, std::uint32_t total_track_count, bool truncated,
                      fmt::memory_buffer& out) {
  auto to = std::back_inserter(out);
  fmt::format_to(
      to,
      R"({{"stream":{},"sequence":{},"frame":{},"pts_ns":{},"captured_ns":{},"latency_ns":{},)"
      R"("frames_dropped":{},"source_outage":{},"truncated":{},"total_tracks":{},"tracks":[)",
      frame.stream_id, frame.sequence, frame.frame_number, frame.pts_ns, frame.times.captured_ns,
      static_cast<std::int64_t>(static_cast<std::uint64_t>(frame.times.sent_ns) -
                                static_cast<std::uint64_t>(frame.times.captured_ns)),
      frame.frames_dropped, frame.source_outage, truncated, total_track_count);
  bool first = true;
  for (const auto& track : frame.tracks) {
    fmt::format_to(to, R"({}{{"id":{},"class":{},"score":)", first ? "" : ",", track.id,
                   track.class_id);
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
  fmt::format_to(to, "]}}\n");
}

JsonlSink::JsonlSink(const std::filesystem::path& path) : file_(path) {}

void JsonlSink::write(const FrameResult& result) {
  write_line(result, static_cast<std::uint32_t>(result.tracks.size()), false);
}

void JsonlSink::write(const DecodedMessage& message) {
  write_line(message.frame, message.total_track_count, message.truncated());
}

void JsonlSink::write_line(const FrameResult& frame, std::uint32_t total_track_count,
                           bool truncated) {
  line_.clear();
  append_json_line(frame, total_track_count, truncated, line_);
  file_.write(line_.data(), line_.size());
}

}  // namespace rtmot::messages
