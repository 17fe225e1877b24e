// Received track messages: decode_message on the raw bytes (it must never throw or read outside
// them), and the same bytes as a length-prefixed message file read back record by record. Every
// message that decodes is also counted by a listener's statistics (few streams: evictions, sequence
// wrap-around and clashes are all reached).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "common/input_error.hpp"
#include "memory_file.hpp"
#include "messages/message_file_reader.hpp"
#include "messages/message_format.hpp"
#include "messages/message_stream_stats.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace rtmot;
  static messages::DecodedMessage decoded;  // reused as a receiver reuses it
  // An exact-size heap copy, so that AddressSanitizer sees any read past the end.
  const std::vector<std::uint8_t> bytes(data, data + size);
  static messages::ListenerStats stats(8);
  if (messages::decode_message(bytes.data(), bytes.size(), decoded) ==
      messages::DecodeError::none) {
    stats.record(decoded);
  }

  static rtmot::fuzz::MemoryFile file;
  try {
    messages::MessageFileReader reader(file.write(data, size));
    std::vector<std::uint8_t> record;
    while (reader.next(record) == messages::FileReadStatus::message) {
      if (messages::decode_message(record.data(), record.size(), decoded) ==
          messages::DecodeError::none) {
        stats.record(decoded);
      }
    }
  } catch (const rtmot::InputError&) {
  }
  return 0;
}
