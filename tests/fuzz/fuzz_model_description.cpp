// A model file as the detector reads its description: the ONNX metadata scan (protobuf's wire
// format, hand-written: detector/onnx_metadata.hpp) and the YAML found there. Only InputError may
// escape.
#include <cstddef>
#include <cstdint>

#include "common/input_error.hpp"
#include "detector/model_description.hpp"
#include "memory_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static rtmot::fuzz::MemoryFile file;
  try {
    // /proc/self/fd/N has no .model.yaml beside it: the description inside is what is read.
    rtmot::detector::read_model_description(file.write(data, size));
  } catch (const rtmot::InputError&) {
  }
  return 0;
}
