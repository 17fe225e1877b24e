#pragma once
// One JSON object per frame and line, for people and scripts (jq, pandas). Field names and meaning:
// docs/message-format.md, "JSON lines".
#include <fmt/format.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string_view>

#include "common/output_file.hpp"
#include "messages/frame_result.hpp"
#include "messages/message_format.hpp"

namespace rtmot::messages {

/// The JSON lines' schema version ("schema"): raised when a field changes meaning or goes away
/// (adding a field does not raise it). docs/message-format.md lists the fields of each version.
constexpr int json_schema_version = 2;

/// A class id's name ("person" for COCO id 1); empty for an unknown id. The messages library knows
/// no label map: a function object, so that a model's own labels (detector/label_table.hpp), a
/// table the caller holds, can answer.
using ClassLabelFn = std::function<std::string_view(int class_id)>;

/// What a JSON line carries beyond the message itself.
struct JsonLineExtras {
  std::int64_t wall_ns{0};  // wall clock (UTC, ns since the epoch) when the line was made
  /// The sink's own function, not a copy (a line is made per frame; copying a function object
  /// that holds a table allocates); nullptr or empty: no "label" field.
  const ClassLabelFn* labels{nullptr};
};

/// Nanoseconds since the Unix epoch on the system (wall) clock.
std::int64_t wall_now_ns();

/// Appends `frame` as one JSON object and a newline to `out`. `total_track_count` and `truncated`
/// describe a received message (a sink writing its own frame passes tracks.size() and false).
void append_json_line(const FrameResult& frame, std::uint32_t total_track_count, bool truncated,
                      const JsonLineExtras& extras, fmt::memory_buffer& out);

class JsonlSink : public TrackSink {
 public:
  /// Creates/truncates `path`; throws InputError naming it if it cannot. `labels` names the
  /// classes in each track's "label" (nullptr: none).
  explicit JsonlSink(const std::filesystem::path& path, ClassLabelFn labels = nullptr);
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
  ClassLabelFn labels_;
  fmt::memory_buffer
      line_;  // reused: formatting allocates nothing once it has held the longest line
};

}  // namespace rtmot::messages
