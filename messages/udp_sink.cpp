#include "messages/udp_sink.hpp"

#include <spdlog/spdlog.h>

#include "common/input_error.hpp"

namespace rtmot::messages {
namespace {

std::size_t checked_payload(std::size_t max_payload, const std::string& destination) {
  if (max_payload < message::min_size || max_payload > message::max_message_size) {
    throw InputError("udp://" + destination, 0, "max_payload",
                     "must be within " + std::to_string(message::min_size) + ".." +
                         std::to_string(message::max_message_size) + " bytes, not " +
                         std::to_string(max_payload),
                     ExitCode::usage);
  }
  return max_payload;
}

}  // namespace

UdpSink::UdpSink(const std::string& host, std::uint16_t port, std::size_t max_payload)
    : sender_(host, port), buffer_(checked_payload(max_payload, sender_.destination())) {}

void UdpSink::write(const FrameResult& result) {
  const std::size_t size = encoder_.encode(result, buffer_.data(), buffer_.size());
  // The message says whether it was cut (flag bit 0, or bit 2 for events): byte 5 of the header.
  if ((buffer_[5] & (message::flag_truncated | message::flag_events_truncated)) != 0) ++truncated_;
  if (sender_.send(buffer_.data(), size)) {
    ++sent_;
    return;
  }
  ++failures_;
  // The first failure and then one in a thousand: a vanished route must not flood the log.
  if (failures_ == 1 || failures_ % 1000 == 0) {
    spdlog::warn("udp://{}: cannot send message {} ({} failures so far): {}", sender_.destination(),
                 result.sequence, failures_, sender_.last_error());
  }
}

}  // namespace rtmot::messages
