#pragma once
// Sends each frame's message as exactly one UDP datagram (message format: docs/message-format.md).
#include <cstdint>
#include <string>
#include <vector>

#include "messages/frame_result.hpp"
#include "messages/message_format.hpp"
#include "platform/udp_socket.hpp"

namespace rtmot::messages {

class UdpSink : public TrackSink {
 public:
  /// Resolves host:port once; throws InputError (network) naming them if that fails.
  /// `max_payload` bounds every datagram (message::min_size .. message::max_message_size); frames
  /// with more tracks than fit send their highest-score tracks, flagged truncated.
  UdpSink(const std::string& host, std::uint16_t port,
          std::size_t max_payload = message::safe_udp_payload);

  /// Never throws: a datagram the kernel refuses is counted (send_failures) and logged, because
  /// a lost datagram is what UDP receivers expect anyway and tracking must go on.
  void write(const FrameResult& result) override;
  /// Datagrams leave at write(): nothing to flush.
  void flush() override {}

  std::uint64_t messages_sent() const { return sent_; }
  std::uint64_t send_failures() const { return failures_; }
  std::uint64_t messages_truncated() const { return truncated_; }
  /// Without the header extension (run id, events: 16 bytes and 24 per event less).
  std::size_t max_tracks_per_message() const { return message::tracks_that_fit(buffer_.size()); }

 private:
  platform::UdpSender sender_;
  MessageEncoder encoder_;
  std::vector<std::uint8_t> buffer_;  // one datagram, allocated once
  std::uint64_t sent_{0};
  std::uint64_t failures_{0};
  std::uint64_t truncated_{0};
};

}  // namespace rtmot::messages
