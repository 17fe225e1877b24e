#include "messages/binary_file_sink.hpp"

#include <algorithm>

namespace rtmot::messages {
namespace {
constexpr std::size_t length_prefix_size = 4;
}

BinaryFileSink::BinaryFileSink(const std::filesystem::path& path, std::size_t max_message_size)
    : file_(path),
      buffer_(length_prefix_size +
              std::clamp(max_message_size, message::min_size, message::max_message_size)) {}

void BinaryFileSink::write(const FrameResult& result) {
  std::uint8_t* const body = buffer_.data() + length_prefix_size;
  const std::size_t size = encoder_.encode(result, body, buffer_.size() - length_prefix_size);
  for (std::size_t i = 0; i < length_prefix_size; ++i) {
    buffer_[i] = static_cast<std::uint8_t>(size >> (8 * i));
  }
  file_.write(buffer_.data(), length_prefix_size + size);
}

}  // namespace rtmot::messages
