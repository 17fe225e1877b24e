// Video source URIs (no GStreamer involved: parsing only). Only InputError may escape.
#include <cstddef>
#include <cstdint>
#include <string>

#include "common/input_error.hpp"
#include "platform/video_uri.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const auto uri = rtmot::platform::parse_video_uri(text);
    rtmot::platform::is_live(uri);
    rtmot::platform::to_string(uri.kind);
  } catch (const rtmot::InputError&) {
  }
  return 0;
}
