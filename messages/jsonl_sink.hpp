#pragma once
// One JSON object per frame and line, for people and scripts (jq, pandas). Field names and meaning:
// docs/message-format.md, "JSON lines".
#include <fmt/format.h>

#include <filesystem>

#include "common/output_file.hpp"
#include "messages/frame_result.hpp"
#include "messages/message_format.hpp"

namespace rtmot::messages {

/// Appends `frame` as one JSON object and a newline to `out`. `total_track_count` and `truncated`
/// describe a received message (a sink writing its own frame passes tracks.size() and false).
void append_json_line(const FrameResult& frame, std::uint32_t total_track_count, bool truncated,
                      fmt::memory_buffer& out);

class JsonlSink : public TrackSink {
 public:
  /// Creates/truncates `path`; throws InputError naming it if it cannot.
  explicit JsonlSink(const std::filesystem::path& path);
  /// Writes its whole buffered lines and closes (flush() reports errors; destructors do not).
  ~JsonlSink() override = default;

  /// Throws InputError naming the file if the stream failed.
  void write(const FrameResult& result) override;
  /// What `rtmot listen --jsonl` writes: a received message, with its truncation.
  void write(const DecodedMessage& message);
  void flush() override { file_.flush(); }

 private:
  void write_line(const FrameResult& frame, std::uint32_t total_track_count, bool truncated);

  OutputFile file_;
  fmt::memory_buffer
      line_;  // reused: formatting allocates nothing once it has held the longest line
};

}  // namespace rtmot::messages
