// det.txt / gt.txt / results rows. The first byte picks the file kind and whether the length check
// applies; the rest is the file. Only InputError may escape the reader.
#include <cstddef>
#include <cstdint>

#include "common/input_error.hpp"
#include "memory_file.hpp"
#include "motio/frame_detections.hpp"
#include "motio/mot_files.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  static rtmot::fuzz::MemoryFile file;
  using namespace rtmot;
  const motio::MotFileKind kinds[] = {motio::MotFileKind::detections,
                                      motio::MotFileKind::ground_truth,
                                      motio::MotFileKind::results};
  const motio::MotFileKind kind = kinds[data[0] % 3];
  const bool with_length = (data[0] & 0x80) != 0;
  const std::string path = file.write(data + 1, size - 1);
  try {
    const auto rows = with_length ? rtmot::motio::read_mot_file(path, kind, 1000)
                                  : rtmot::motio::read_mot_file(path, kind);
    // Sparse: any frame number costs only its rows.
    const rtmot::motio::FrameDetections frames(rows);
    std::size_t boxes = 0;
    for (const auto& row : rows) boxes += frames.at(row.frame).size();
    (void)boxes;
  } catch (const rtmot::InputError&) {
  }
  return 0;
}
