// The YAML run configuration, parsed and validated. Only InputError may escape (a yaml-cpp
// exception getting out would be a finding: the user would see "internal error").
#include <cstddef>
#include <cstdint>
#include <string>

#include "common/input_error.hpp"
#include "runner/run_config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const auto config = rtmot::runner::parse_run_config(text, "fuzz.yaml");
    rtmot::runner::validate(config);
  } catch (const rtmot::InputError&) {
  }
  return 0;
}
