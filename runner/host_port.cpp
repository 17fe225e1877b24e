#include "runner/host_port.hpp"

#include "common/input_error.hpp"

namespace rtmot::runner {

HostPort parse_host_port(const std::string& text, const std::string& file, int line,
                         const std::string& field, ExitCode code) {
  const auto bad = [&](const std::string& why) {
    return InputError(file, line, field,
                      "expected HOST:PORT with a port in 1..65535, got '" + text + "'" +
                          (why.empty() ? "" : ": " + why),
                      code);
  };
  const auto colon = text.rfind(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == text.size()) throw bad("");
  const std::string digits = text.substr(colon + 1);
  if (digits.size() > 5 || digits.find_first_not_of("0123456789") != std::string::npos) {
    throw bad("the port is not a number in 1..65535");
  }
  const int port = std::stoi(digits);
  if (port < 1 || port > 65535) throw bad("the port is outside 1..65535");
  std::string host = text.substr(0, colon);
  if (host.size() > 2 && host.front() == '[' && host.back() == ']') {
    host = host.substr(1, host.size() - 2);
  } else if (host.find(':') != std::string::npos) {
    throw bad("write an IPv6 address in brackets, e.g. [::1]:5600");
  }
  return {host, static_cast<std::uint16_t>(port)};
}

}  // namespace rtmot::runner
