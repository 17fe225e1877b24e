// HOST:PORT as the run configuration and --udp give it (runner/host_port.hpp): any bytes, and only
// InputError may escape; a result's port is always in 1..65535.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "common/input_error.hpp"
#include "runner/host_port.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const auto parsed = rtmot::runner::parse_host_port(text, "fuzz.yaml", 1, "output.udp",
                                                       rtmot::ExitCode::bad_input);
    if (parsed.port == 0 || parsed.host.empty()) std::abort();
  } catch (const rtmot::InputError&) {
  }
  return 0;
}
