#include "messages/message_file_reader.hpp"

#include "common/input_error.hpp"
#include "messages/message_format.hpp"

namespace rtmot::messages {

MessageFileReader::MessageFileReader(const std::filesystem::path& path) : file_(path) {}

FileReadStatus MessageFileReader::next(std::vector<std::uint8_t>& bytes) {
  std::uint8_t prefix[4] = {};
  const std::size_t got = file_.read(prefix, sizeof prefix);
  if (got == 0) return FileReadStatus::end_of_file;
  if (got != sizeof prefix)
    return broken("length prefix cut after " + std::to_string(got) + " bytes");
  const std::uint32_t length =
      static_cast<std::uint32_t>(prefix[0]) | static_cast<std::uint32_t>(prefix[1]) << 8 |
      static_cast<std::uint32_t>(prefix[2]) << 16 | static_cast<std::uint32_t>(prefix[3]) << 24;
  // Checked before allocating: a flipped bit in a length must not ask for gigabytes.
  if (length > message::max_message_size) {
    return broken("record length " + std::to_string(length) + " above the maximum " +
                  std::to_string(message::max_message_size));
  }
  bytes.resize(length);
  const std::size_t body = file_.read(bytes.data(), length);
  if (body != length) {
    return broken("record of " + std::to_string(length) + " bytes cut after " +
                  std::to_string(body));
  }
  offset_ += sizeof prefix + length;
  ++records_;
  return FileReadStatus::message;
}

FileReadStatus MessageFileReader::broken(const std::string& what) {
  problem_ = "record " + std::to_string(records_ + 1) + " at byte " + std::to_string(offset_) +
             ": " + what;
  return FileReadStatus::broken_framing;
}

}  // namespace rtmot::messages
