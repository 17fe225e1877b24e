#include "platform/host_port.hpp"

#include <arpa/inet.h>

#include <algorithm>
#include <cctype>

namespace rtmot::platform {
namespace {

bool is_ipv4(const std::string& text) {
  in_addr address{};
  return ::inet_pton(AF_INET, text.c_str(), &address) == 1;
}

bool is_ipv6(const std::string& text) {
  // A scope (fe80::1%eth0) names an interface; inet_pton reads the address before it.
  const std::string address = text.substr(0, text.find('%'));
  in6_addr parsed{};
  return address.size() + 1 != text.size() && ::inet_pton(AF_INET6, address.c_str(), &parsed) == 1;
}

bool is_label_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '-' || c == '_';
}

std::string name_problem(std::string_view name) {
  if (name.size() > 253) return "a host name has at most 253 characters";
  std::string_view last;
  std::size_t start = 0;
  while (start <= name.size()) {
    const std::size_t dot = std::min(name.find('.', start), name.size());
    const std::string_view label = name.substr(start, dot - start);
    // A trailing dot (the root) is allowed: "example.com."
    if (label.empty() && dot == name.size() && start > 0) break;
    if (label.empty() || label.size() > 63 || label.front() == '-' || label.back() == '-' ||
        !std::all_of(label.begin(), label.end(), is_label_char)) {
      return "'" + std::string(name) + "' is not a host name or an IP address";
    }
    last = label;
    start = dot + 1;
  }
  if (std::all_of(last.begin(), last.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    return "'" + std::string(name) + "' is not an IPv4 address (four numbers 0..255)";
  }
  return {};
}

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

std::string host_problem(std::string_view host) {
  const std::string text(host);
  if (text.empty()) return "missing host";
  if (text.find(':') != std::string::npos) {
    return is_ipv6(text) ? std::string{} : "'" + text + "' is not an IPv6 address";
  }
  if (is_ipv4(text)) return {};
  return name_problem(text);
}

std::optional<std::string> parse_bind_address(std::string_view text, std::string& problem) {
  std::string address(text);
  if (address.size() >= 2 && address.front() == '[' && address.back() == ']') {
    address = address.substr(1, address.size() - 2);
  }
  if (is_ipv4(address) || is_ipv6(address)) return address;
  problem = "'" + std::string(text) + "' is not an IPv4 or IPv6 address to listen on";
  return std::nullopt;
}

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
  problem = host_problem(result.host);
  if (!problem.empty()) return std::nullopt;
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
