#pragma once
// The one parser of network addresses given by users: `HOST:PORT`, `[IPV6]:PORT`, and the
// authority part of URIs (udp://, rtp://, mqtt://). Used by every output and the listener, so that
// `[::1]:5600` means the same thing everywhere.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace rtmot::platform {

struct HostPort {
  std::string host;  // a name, an IPv4 literal or an IPv6 literal without brackets
  std::uint16_t port{0};
};

/// Checks a host as users give it: an IPv4 address (four numbers 0..255), an IPv6 address, or a DNS
/// name (labels of letters, digits, '-' and '_', 1..63 characters, not starting or ending with '-';
/// the last label not all digits, so that `999.999.1.1` is refused as an IPv4 address, not looked
/// up as a name). Returns the problem, empty when `host` is one.
std::string host_problem(std::string_view host);

/// A local address to bind: an IPv4 or IPv6 literal (brackets around IPv6 allowed), never a name.
/// Returns it without brackets, or nullopt and sets `problem`.
std::optional<std::string> parse_bind_address(std::string_view text, std::string& problem);

/// Parses `HOST:PORT` or `[IPV6]:PORT`; the host is checked by host_problem(). The port must
/// be 1..65535 unless `allow_port_zero` (for binding an ephemeral port); with `default_port`
/// non-zero, a missing `:PORT` takes it. Returns nullopt and sets `problem` (one phrase, e.g. "port
/// 70000 is out of range 1..65535") if malformed.
std::optional<HostPort> parse_host_port(std::string_view text, std::string& problem,
                                        std::uint16_t default_port = 0,
                                        bool allow_port_zero = false);

/// `host:port`, with brackets around an IPv6 literal: what parse_host_port reads back.
std::string format_host_port(const std::string& host, std::uint16_t port);

}  // namespace rtmot::platform
