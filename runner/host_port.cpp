#include "runner/host_port.hpp"

#include "common/input_error.hpp"

namespace rtmot::runner {

HostPort parse_host_port(const std::string& text, const std::string& file, int line,
                         const std::string& field, ExitCode code) {
  std::string problem;
  const auto parsed = platform::parse_host_port(text, problem);
  if (!parsed) {
    throw InputError(file, line, field,
                     "expected HOST:PORT or [IPV6]:PORT, got '" + text + "': " + problem, code);
  }
  return *parsed;
}

}  // namespace rtmot::runner
