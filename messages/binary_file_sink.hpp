#pragma once
// Writes each frame's message to a file, each preceded by its length (u32, little-endian), so that
// the file is a replayable record of what UDP would have carried. Read back with MessageFileReader.
#include <cstdint>
#include <filesystem>
#include <vector>

#include "common/output_file.hpp"
#include "messages/frame_result.hpp"
#include "messages/message_format.hpp"

namespace rtmot::messages {

class BinaryFileSink : public TrackSink {
 public:
  /// Creates/truncates `path` (throws InputError naming it if it cannot). Unlike UDP there is no
  /// datagram limit: `max_message_size` bounds one message (default: every track of any real
  /// frame).
  explicit BinaryFileSink(const std::filesystem::path& path,
                          std::size_t max_message_size = message::max_message_size);
  /// Writes its whole buffered messages and closes (flush() reports errors; destructors do not).
  ~BinaryFileSink() override = default;

  /// Throws InputError naming the file if the stream failed (disk full, I/O error).
  void write(const FrameResult& result) override;
  void flush() override { file_.flush(); }

 private:
  OutputFile file_;  // whole records: a reader never sees half a message
  MessageEncoder encoder_;
  std::vector<std::uint8_t> buffer_;  // length prefix + one message, allocated once
};

}  // namespace rtmot::messages
