// HOST:PORT as the run configuration and --udp give it (the output.udp setting of
// runner/run_settings.hpp, parsed by platform/host_port.hpp): any bytes, nothing may escape; a
// value taken has a host and a port in 1..65535.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "runner/run_settings.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  static const rtmot::runner::RunSetting* const udp = rtmot::runner::find_run_setting("output.udp");
  rtmot::runner::RunConfig config;
  std::string problem;
  if (udp->set(config, text, problem) && !text.empty()) {
    if (!config.output.udp || config.output.udp->port == 0 || config.output.udp->host.empty())
      std::abort();
  }
  return 0;
}
