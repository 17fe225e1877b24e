// Cost per frame of the track message: encoding (with and without truncation), decoding with every
// check, and the JSON line. Frames are MOT-like: person boxes spread over a 1920x1080 image.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "messages/jsonl_sink.hpp"
#include "messages/message_format.hpp"

namespace {

using namespace rtmot::messages;

FrameResult crowd(std::size_t tracks) {
  std::mt19937 random(42);
  std::uniform_real_distribution<float> x(0.F, 1800.F), y(0.F, 700.F), h(80.F, 380.F),
      score(0.5F, 1.F);
  FrameResult frame;
  frame.stream_id = 1;
  frame.sequence = 1234;
  frame.frame_number = 1235;
  frame.pts_ns = 41'133'333'000;
  frame.times.captured_ns = 9'000'000'000'000;
  frame.times.sent_ns = frame.times.captured_ns + 52'000'000;
  for (std::size_t i = 0; i < tracks; ++i) {
    rtmot::tracker::TrackReport track;
    track.id = static_cast<std::int32_t>(100 + i);
    track.box.h = h(random);
    track.box = {x(random), y(random), track.box.h * 0.41F, track.box.h};
    track.score = score(random);
    track.class_id = 1;
    track.hits = 12;
    track.age = 40;
    frame.tracks.push_back(track);
  }
  return frame;
}

void BM_Encode(benchmark::State& state) {
  const FrameResult frame = crowd(static_cast<std::size_t>(state.range(0)));
  std::vector<std::uint8_t> buffer(message::safe_udp_payload);
  MessageEncoder encoder;
  for (auto _ : state)
    benchmark::DoNotOptimize(encoder.encode(frame, buffer.data(), buffer.size()));
  state.SetItemsProcessed(state.iterations());
}
// 20 tracks: a busy street; 35: the most one datagram holds; 200: truncated to 35 by score.
BENCHMARK(BM_Encode)->Arg(0)->Arg(20)->Arg(35)->Arg(200);

void BM_Decode(benchmark::State& state) {
  const FrameResult frame = crowd(static_cast<std::size_t>(state.range(0)));
  std::vector<std::uint8_t> buffer(message::safe_udp_payload);
  MessageEncoder encoder;
  buffer.resize(encoder.encode(frame, buffer.data(), buffer.size()));
  DecodedMessage decoded;
  for (auto _ : state)
    benchmark::DoNotOptimize(decode_message(buffer.data(), buffer.size(), decoded));
  state.SetItemsProcessed(state.iterations());
  state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(buffer.size()));
}
BENCHMARK(BM_Decode)->Arg(0)->Arg(20)->Arg(35);

void BM_JsonLine(benchmark::State& state) {
  const FrameResult frame = crowd(static_cast<std::size_t>(state.range(0)));
  fmt::memory_buffer line;
  for (auto _ : state) {
    line.clear();
    append_json_line(frame, static_cast<std::uint32_t>(frame.tracks.size()), false,
                     JsonLineExtras{wall_now_ns(), nullptr}, line);
    benchmark::DoNotOptimize(line.data());
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_JsonLine)->Arg(20);

}  // namespace
