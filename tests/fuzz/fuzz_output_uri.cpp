// The outputs' parsers of user text (command line, YAML): HOST:PORT, mqtt:// and video target URIs,
// overlay flags. None may crash or throw: each returns nullopt with a problem.
#include <cstddef>
#include <cstdint>
#include <string>

#include "outputs/mqtt_uri.hpp"
#include "outputs/overlay.hpp"
#include "outputs/video_target.hpp"
#include "platform/host_port.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::string problem;
  rtmot::platform::parse_host_port(text, problem, 0, size % 2 == 0);
  rtmot::platform::parse_host_port(text, problem, 1883);
  if (const auto uri = rtmot::outputs::parse_mqtt_uri(text, problem)) {
    rtmot::outputs::to_string(*uri);
  }
  rtmot::outputs::parse_video_target(text, problem);
  rtmot::outputs::parse_overlay_flags(text, problem);
  return 0;
}
