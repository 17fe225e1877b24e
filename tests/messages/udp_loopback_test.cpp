// UdpSink to a UdpReceiver over 127.0.0.1: every message arrives, whole, in one datagram.
#include <gtest/gtest.h>

#include <tuple>
#include <vector>

#include "common/input_error.hpp"
#include "message_test_data.hpp"
#include "messages/udp_sink.hpp"
#include "platform/udp_socket.hpp"

namespace rtmot::messages {
namespace {

constexpr int receive_timeout_ms = 2000;  // generous: only a lost datagram ever waits this long

TEST(UdpLoopback, EveryMessageArrivesDecodedEqual) {
  platform::UdpReceiver receiver("127.0.0.1", 0);
  ASSERT_NE(receiver.port(), 0);
  UdpSink sink("127.0.0.1", receiver.port());
  const auto frames = test::frames_from_detections("ETH-Bahnhof", 400);
  ASSERT_EQ(frames.size(), 400U);

  std::vector<std::uint8_t> datagram(message::max_message_size);
  DecodedMessage decoded;
  // Paced in bursts well inside the socket's receive buffer: loopback then loses nothing.
  constexpr std::size_t burst = 16;
  for (std::size_t start = 0; start < frames.size(); start += burst) {
    const std::size_t end = std::min(frames.size(), start + burst);
    for (std::size_t i = start; i < end; ++i) sink.write(frames[i]);
    for (std::size_t i = start; i < end; ++i) {
      std::size_t size = 0;
      bool truncated = false;
      ASSERT_EQ(
          receiver.receive(datagram.data(), datagram.size(), receive_timeout_ms, size, truncated),
          platform::ReceiveStatus::datagram)
          << "message " << i << " did not arrive";
      ASSERT_FALSE(truncated);
      ASSERT_EQ(decode_message(datagram.data(), size, decoded), DecodeError::none)
          << "message " << i;
      ASSERT_TRUE(test::same_as_sent(frames[i], decoded));
    }
  }
  EXPECT_EQ(sink.messages_sent(), frames.size());
  EXPECT_EQ(sink.send_failures(), 0U);
}

TEST(UdpLoopback, CrowdsTravelTruncatedInOneSafeDatagram) {
  platform::UdpReceiver receiver("127.0.0.1", 0);
  UdpSink sink("127.0.0.1", receiver.port());
  sink.write(test::crowd_from_detections("ETH-Bahnhof", 120));
  std::vector<std::uint8_t> datagram(message::max_message_size);
  std::size_t size = 0;
  bool truncated = false;
  ASSERT_EQ(receiver.receive(datagram.data(), datagram.size(), receive_timeout_ms, size, truncated),
            platform::ReceiveStatus::datagram);
  EXPECT_LE(size, message::safe_udp_payload);
  DecodedMessage decoded;
  ASSERT_EQ(decode_message(datagram.data(), size, decoded), DecodeError::none);
  EXPECT_TRUE(decoded.truncated());
  EXPECT_EQ(decoded.total_track_count, 120U);
  EXPECT_EQ(decoded.frame.tracks.size(), sink.max_tracks_per_message());
  EXPECT_EQ(sink.messages_truncated(), 1U);
  // Nothing else was sent: one frame, one datagram.
  EXPECT_EQ(receiver.receive(datagram.data(), datagram.size(), 50, size, truncated),
            platform::ReceiveStatus::timeout);
}

TEST(UdpLoopback, AnOversizedDatagramIsReportedCut) {
  platform::UdpReceiver receiver("127.0.0.1", 0);
  platform::UdpSender sender("127.0.0.1", receiver.port());
  const std::vector<std::uint8_t> big(3000, 0xAB);
  ASSERT_TRUE(sender.send(big.data(), big.size())) << sender.last_error();
  std::vector<std::uint8_t> small(1000);
  std::size_t size = 0;
  bool truncated = false;
  ASSERT_EQ(receiver.receive(small.data(), small.size(), receive_timeout_ms, size, truncated),
            platform::ReceiveStatus::datagram);
  EXPECT_TRUE(truncated);
  EXPECT_EQ(size, small.size());
}

TEST(UdpSocketErrors, PortInUseNamesThePortAndIsANetworkError) {
  platform::UdpReceiver first("127.0.0.1", 0);
  try {
    platform::UdpReceiver second("127.0.0.1", first.port());
    FAIL() << "bound port " << first.port() << " twice";
  } catch (const InputError& error) {
    EXPECT_EQ(error.exit_code(), ExitCode::network);
    EXPECT_NE(std::string(error.what()).find(std::to_string(first.port())), std::string::npos)
        << error.what();
    EXPECT_NE(std::string(error.what()).find("in use"), std::string::npos) << error.what();
  }
}

TEST(UdpSocketErrors, BadDestinationsNameHostAndPort) {
  // No unresolvable DNS name here: resolving one would send a query off this machine.
  for (const auto& [host, port, named] :
       {std::tuple<const char*, std::uint16_t, const char*>{"", 9999, ":9999"},
        {"127.0.0.1", 0, "127.0.0.1:0"}}) {
    try {
      UdpSink sink(host, port);
      FAIL() << "accepted '" << host << "' port " << port;
    } catch (const InputError& error) {
      EXPECT_EQ(error.exit_code(), ExitCode::network);
      EXPECT_NE(std::string(error.what()).find(named), std::string::npos) << error.what();
    }
  }
}

TEST(UdpSocketErrors, BindingAnAddressThatIsNotLocalFails) {
  // 192.0.2.1 is TEST-NET-1 (RFC 5737): never assigned to a host, so bind() fails; nothing is sent.
  EXPECT_THROW(platform::UdpReceiver("192.0.2.1", 0), InputError);
  EXPECT_THROW(UdpSink("127.0.0.1", 9999, 10), InputError);  // a payload limit below the header
}

}  // namespace
}  // namespace rtmot::messages
