// seqinfo.ini. Only InputError may escape the reader.
#include <cstddef>
#include <cstdint>

#include "common/input_error.hpp"
#include "memory_file.hpp"
#include "motio/mot_files.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static rtmot::fuzz::MemoryFile file;
  try {
    rtmot::motio::read_seqinfo(file.write(data, size));
  } catch (const rtmot::InputError&) {
  }
  return 0;
}
