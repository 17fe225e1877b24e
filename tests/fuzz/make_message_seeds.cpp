// Seeds for fuzz_message_decoder from real data: the ground truth of a MOT sequence turned into
// track messages (one file per frame) and one length-prefixed message file as BinaryFileSink
// writes it. Usage: make_message_seeds GT_TXT OUT_DIR
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <vector>

#include "messages/binary_file_sink.hpp"
#include "messages/message_format.hpp"
#include "motio/mot_files.hpp"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s GT_TXT OUT_DIR\n", argv[0]);
    return 2;
  }
  using namespace rtmot;
  const std::filesystem::path out_dir = argv[2];
  std::filesystem::create_directories(out_dir);
  std::map<int, messages::FrameResult> frames;
  for (const auto& row : motio::read_mot_file(argv[1], motio::MotFileKind::ground_truth)) {
    if (row.frame > 20) continue;
    auto& frame = frames[row.frame];
    frame.frame_number = row.frame;
    frame.sequence = static_cast<std::uint64_t>(row.frame - 1);
    frame.pts_ns = (row.frame - 1) * 100'000'000LL;
    frame.times.captured_ns = 1'000'000'000LL + frame.pts_ns;
    frame.times.sent_ns = frame.times.captured_ns + 60'000'000LL;
    frame.tracks.push_back({row.id, row.box, row.conf, 1, 3, row.frame});
  }
  messages::MessageEncoder encoder;
  std::vector<std::uint8_t> buffer(messages::message::max_message_size);
  messages::BinaryFileSink file_sink(out_dir / "messages-file.bin");
  for (const auto& [number, frame] : frames) {
    const std::size_t size = encoder.encode(frame, buffer.data(), buffer.size());
    std::ofstream(out_dir / ("message-" + std::to_string(number) + ".bin"), std::ios::binary)
        .write(reinterpret_cast<const char*>(buffer.data()), static_cast<std::streamsize>(size));
    // A message cut to the safe UDP payload: exercises the truncated flag.
    const std::size_t cut =
        encoder.encode(frame, buffer.data(), messages::message::safe_udp_payload / 4);
    std::ofstream(out_dir / ("message-" + std::to_string(number) + "-truncated.bin"),
                  std::ios::binary)
        .write(reinterpret_cast<const char*>(buffer.data()), static_cast<std::streamsize>(cut));
    file_sink.write(frame);
  }
  file_sink.flush();
  return 0;
}
