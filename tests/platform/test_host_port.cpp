// The one HOST:PORT parser, and that what it parses reaches a real socket (IPv6 loopback included).
#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "platform/host_port.hpp"
#include "platform/udp_socket.hpp"

namespace rtmot::platform {
namespace {

HostPort parsed(const std::string& text, std::uint16_t default_port = 0) {
  std::string problem;
  const auto result = parse_host_port(text, problem, default_port);
  EXPECT_TRUE(result.has_value()) << text << ": " << problem;
  return result.value_or(HostPort{});
}

std::string problem_of(const std::string& text, bool allow_zero = false) {
  std::string problem;
  EXPECT_FALSE(parse_host_port(text, problem, 0, allow_zero).has_value()) << text;
  return problem;
}

TEST(HostPort, ReadsNamesIpv4AndBracketedIpv6) {
  EXPECT_EQ(parsed("localhost:5600").host, "localhost");
  EXPECT_EQ(parsed("localhost:5600").port, 5600);
  EXPECT_EQ(parsed("192.168.1.20:1").host, "192.168.1.20");
  EXPECT_EQ(parsed("[::1]:5600").host, "::1");
  EXPECT_EQ(parsed("[::1]:5600").port, 5600);
  EXPECT_EQ(parsed("[fe80::1%eth0]:65535").host, "fe80::1%eth0");
  EXPECT_EQ(parsed("[fe80::1%eth0]:65535").port, 65535);
}

TEST(HostPort, DefaultPortOnlyWhenGiven) {
  EXPECT_EQ(parsed("broker", 1883).port, 1883);
  EXPECT_EQ(parsed("[::1]", 1883).host, "::1");
  EXPECT_EQ(problem_of("broker"), "missing ':PORT'");
}

TEST(HostPort, SaysWhatIsWrong) {
  EXPECT_EQ(problem_of("::1:5600"), "an IPv6 address needs brackets: [ADDRESS]:PORT");
  EXPECT_EQ(problem_of("[::1:5600"), "'[' without ']' around an IPv6 address");
  EXPECT_EQ(problem_of("[::1]5600"), "expected ':PORT' after ']'");
  EXPECT_EQ(problem_of(":5600"), "missing host");
  EXPECT_EQ(problem_of("[]:5600"), "missing host");
  EXPECT_EQ(problem_of("host:"), "missing port");
  EXPECT_EQ(problem_of("host:56a"), "port '56a' is not a number");
  EXPECT_EQ(problem_of("host:70000"), "port 70000 is out of range 1..65535");
  EXPECT_EQ(problem_of("host:99999999999999999999"),
            "port 99999999999999999999 is out of range 1..65535");
  EXPECT_EQ(problem_of("host:0"), "port 0 is out of range 1..65535");
  std::string problem;
  EXPECT_TRUE(parse_host_port("host:0", problem, 0, true).has_value());
}

// Issue 23, class 5: `999.999.1.1` was looked up as a name and listened on 231.231.1.1.
TEST(HostPort, RefusesWhatIsNotAnAddress) {
  EXPECT_EQ(problem_of("999.999.1.1:5600"),
            "'999.999.1.1' is not an IPv4 address (four numbers 0..255)");
  EXPECT_EQ(problem_of("1.2.3:5600"), "'1.2.3' is not an IPv4 address (four numbers 0..255)");
  EXPECT_EQ(problem_of("[::g]:5600"), "'::g' is not an IPv6 address");
  EXPECT_EQ(problem_of("ground station:5600"),
            "'ground station' is not a host name or an IP address");
  EXPECT_EQ(problem_of("-bad.example:5600"), "'-bad.example' is not a host name or an IP address");
  EXPECT_EQ(problem_of("a..b:5600"), "'a..b' is not a host name or an IP address");
  EXPECT_EQ(parsed("ground-station.local:5600").host, "ground-station.local");
  EXPECT_EQ(parsed("example.com.:5600").host, "example.com.");
  EXPECT_EQ(parsed("[fe80::1%eth0]:5600").host, "fe80::1%eth0");
  EXPECT_EQ(parsed("255.255.255.255:5600").host, "255.255.255.255");
}

TEST(HostPort, BindAddressIsAnIpLiteral) {
  std::string problem;
  EXPECT_EQ(parse_bind_address("0.0.0.0", problem).value_or(""), "0.0.0.0");
  EXPECT_EQ(parse_bind_address("[::1]", problem).value_or(""), "::1");
  EXPECT_EQ(parse_bind_address("::", problem).value_or(""), "::");
  for (const char* bad : {"999.999.1.1", "localhost", "", "[::1", "1.2.3.4:80"}) {
    EXPECT_FALSE(parse_bind_address(bad, problem).has_value()) << bad;
    EXPECT_NE(problem.find("is not an IPv4 or IPv6 address"), std::string::npos) << problem;
  }
}

TEST(HostPort, FormatReadsBack) {
  EXPECT_EQ(format_host_port("::1", 5600), "[::1]:5600");
  EXPECT_EQ(format_host_port("127.0.0.1", 5600), "127.0.0.1:5600");
  EXPECT_EQ(parsed(format_host_port("::1", 42)).host, "::1");
}

// What issue 9 found: `[::1]:5600` failed with "cannot resolve host". Parsed by the one parser, it
// now carries a datagram over the IPv6 loopback.
TEST(HostPort, Ipv6LoopbackTargetCarriesADatagram) {
  UdpReceiver receiver("::1", 0);
  const HostPort target = parsed("[::1]:" + std::to_string(receiver.port()));
  UdpSender sender(target.host, target.port);
  const std::uint8_t payload[3] = {1, 2, 3};
  ASSERT_TRUE(sender.send(payload, sizeof payload)) << sender.last_error();
  std::uint8_t buffer[16]{};
  std::size_t size = 0;
  bool truncated = false;
  ASSERT_EQ(receiver.receive(buffer, sizeof buffer, 2000, size, truncated),
            ReceiveStatus::datagram);
  EXPECT_EQ(size, 3U);
  EXPECT_EQ(buffer[2], 3);
}

}  // namespace
}  // namespace rtmot::platform
