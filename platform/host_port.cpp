#include "platform/host_port.hpp"

namespace rtmot::platform {
namespace {

bool parse_port(std::string_view digits, bool allow_zero, std::uint16_t& port,
                std::string& problem) {
  if (digits.empty()) {
    problem = "missing port";
    return false;
  }
  std::uint32_t value = 0;
  for (const char c : digits) {
    if (c < '0' || c > '9') {
      problem = "port '" + std::string(digits) + "' is not a number";
      return false;
    }
    value = value * 10 + static_cast<std::uint32_t>(c - '0');
    if (value > 65535) break;  // stop before a long digit string can overflow
  }
  if (value > 65535 || (value == 0 && !allow_zero)) {
    problem =
        "port " + std::string(digits) + " is out of range " + (allow_zero ? "0" : "1") + "..65535";
    return false;
  }
  port = static_cast<std::uint16_t>(value);
  return true;
}

}  // namespace

std::optional<HostPort> parse_host_port(std::string_view text, std::string& problem,
                                        std::uint16_t default_port, bool allow_port_zero) {
  HostPort result;
  std::string_view rest;
  if (!text.empty() && text.front() == '[') {
    const auto close = text.find(']');
    if (close == std::string_view::npos) {
      problem = "'[' without ']' around an IPv6 address";
      return std::nullopt;
    }
    result.host = std::string(text.substr(1, close - 1));
    rest = text.substr(close + 1);
    if (!rest.empty() && rest.front() != ':') {
      problem = "expected ':PORT' after ']'";
      return std::nullopt;
    }
  } else {
    const auto colon = text.find(':');
    if (colon != std::string_view::npos && text.find(':', colon + 1) != std::string_view::npos) {
      problem = "an IPv6 address needs brackets: [ADDRESS]:PORT";
      return std::nullopt;
    }
    result.host = std::string(text.substr(0, colon));
    if (colon != std::string_view::npos) rest = text.substr(colon);
  }
  if (result.host.empty()) {
    problem = "missing host";
    return std::nullopt;
  }
  if (rest.empty()) {
    if (default_port == 0) {
      problem = "missing ':PORT'";
      return std::nullopt;
    }
    result.port = default_port;
    return result;
  }
  if (!parse_port(rest.substr(1), allow_port_zero, result.port, problem)) return std::nullopt;
  return result;
}

std::string format_host_port(const std::string& host, std::uint16_t port) {
  const bool ipv6_literal = host.find(':') != std::string::npos;
  return (ipv6_literal ? "[" + host + "]" : host) + ":" + std::to_string(port);
}

}  // namespace rtmot::platform
