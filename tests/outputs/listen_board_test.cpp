// What the ground station's page shows (outputs/listen_board.hpp), fed as `rtmot listen` feeds it:
// PETS09-S2L1's detections encoded as track messages, decoded and counted by ListenerStats, with a
// lost and a late message, a board whose clocks are wrong, a silent stream, and more streams than
// the page shows.
#include "outputs/listen_board.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "message_test_data.hpp"
#include "messages/message_stream_stats.hpp"

namespace rtmot::outputs {
namespace {

constexpr std::int64_t kSecond = 1'000'000'000;

class Listener {
 public:
  Listener() : board_([](int) { return std::string_view("person"); }, 0) {}

  void hear(const messages::FrameResult& frame, std::int64_t received_ns) {
    std::vector<std::uint8_t> buffer(messages::message::safe_udp_payload);
    const std::size_t size = encoder_.encode(frame, buffer.data(), buffer.size());
    ASSERT_EQ(messages::decode_message(buffer.data(), size, decoded_), messages::DecodeError::none);
    const auto arrival = stats_.record(decoded_);
    board_.record(decoded_, arrival, stats_.streams().at(frame.stream_id), received_ns);
  }
  nlohmann::json page(std::int64_t now_ns) const { return board_.to_json(now_ns); }

 private:
  messages::MessageEncoder encoder_;
  messages::DecodedMessage decoded_;
  messages::ListenerStats stats_;
  ListenBoard board_;
};

std::vector<messages::FrameResult> pets(std::uint32_t stream_id) {
  auto frames = test::frames_from_detections("PETS09-S2L1", 40);
  for (auto& frame : frames) {
    frame.stream_id = stream_id;
    frame.run_id = 0x1234;
    frame.frame_width = 768;
    frame.frame_height = 576;
    // A board whose clock is wrong by years: nothing shown may depend on it.
    frame.times.captured_ns += 400LL * 24 * 3600 * kSecond;
  }
  return frames;
}

TEST(ListenBoard, ShowsTheNewestTracksTheFrameSizeAndTheLossesOfEachStream) {
  Listener listener;
  const auto frames = pets(7);
  std::int64_t now = 100 * kSecond;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    if (i == 20 || i == 30) continue;  // 20 is lost; 30 arrives late, after 31
    listener.hear(frames[i], now);
    if (i == 31) listener.hear(frames[30], now);
    now += kSecond / 10;  // 10 messages a second, by the listener's clock
  }
  const nlohmann::json page = listener.page(now);
  ASSERT_EQ(page["streams"].size(), 1U);
  const nlohmann::json& stream = page["streams"][0];
  EXPECT_EQ(stream["stream"], 7);
  EXPECT_EQ(stream["run"], "0000000000001234");
  EXPECT_EQ(stream["width"], 768);
  EXPECT_EQ(stream["height"], 576);
  EXPECT_EQ(stream["received"], 39);
  EXPECT_EQ(stream["lost"], 1);
  EXPECT_EQ(stream["reordered"], 1);
  EXPECT_EQ(stream["restarts"], 0);
  EXPECT_TRUE(stream["up"]);
  // The late message did not replace the newest one's tracks.
  const auto& last = frames.back();
  EXPECT_EQ(stream["sequence"], last.sequence);
  ASSERT_EQ(stream["tracks"].size(), last.tracks.size());
  ASSERT_FALSE(last.tracks.empty());
  EXPECT_EQ(stream["tracks"][0]["id"], last.tracks[0].id);
  EXPECT_EQ(stream["tracks"][0]["x"].get<float>(), last.tracks[0].box.x);
  EXPECT_EQ(stream["tracks"][0]["label"], "person");
  // Ages and rates by the listener's clock, whatever the board's says.
  EXPECT_NEAR(stream["age_s"].get<double>(), 0.1, 1e-9);
  EXPECT_NEAR(stream["rate"].get<double>(), 10.0, 1.0);
  // Silent for longer than ListenBoard::kDownAfterNs: down, rate 0, tracks kept.
  const nlohmann::json later = listener.page(now + 4 * kSecond);
  EXPECT_FALSE(later["streams"][0]["up"]);
  EXPECT_EQ(later["streams"][0]["rate"], 0.0);
  EXPECT_EQ(later["streams"][0]["tracks"].size(), last.tracks.size());
}

TEST(ListenBoard, ShowsAtMostItsBoundOfStreamsTheMostRecentlyHeard) {
  Listener listener;
  auto frame = pets(0).front();
  const std::size_t heard = ListenBoard::kMaxStreams + 5;
  for (std::size_t i = 0; i < heard; ++i) {
    frame.stream_id = static_cast<std::uint32_t>(1000 + i);
    listener.hear(frame, static_cast<std::int64_t>(i) * kSecond);
  }
  const nlohmann::json page = listener.page(static_cast<std::int64_t>(heard) * kSecond);
  ASSERT_EQ(page["streams"].size(), ListenBoard::kMaxStreams);
  EXPECT_EQ(page["streams_evicted"], 5);
  EXPECT_EQ(page["streams"][0]["stream"], 1005);  // the first five, heard least recently, went
  EXPECT_EQ(page["received"], heard);
}

}  // namespace
}  // namespace rtmot::outputs
