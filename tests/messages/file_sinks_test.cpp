// The binary file and JSON-lines sinks: what they write, a reader reads back.
#include <gtest/gtest.h>

#include <cmath>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "common/input_error.hpp"
#include "message_test_data.hpp"
#include "messages/binary_file_sink.hpp"
#include "messages/jsonl_sink.hpp"
#include "messages/message_file_reader.hpp"

namespace rtmot::messages {
namespace {

class FileSinks : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    directory_ = std::filesystem::temp_directory_path() /
                 (std::string("rtmot-messages-") + info->name() + "-" + std::to_string(::getpid()));
    std::filesystem::create_directories(directory_);
  }
  void TearDown() override { std::filesystem::remove_all(directory_); }
  std::filesystem::path file(const std::string& name) const { return directory_ / name; }

 private:
  std::filesystem::path directory_;
};

TEST_F(FileSinks, BinaryFileReadsBackEveryMessage) {
  const auto frames = test::frames_from_detections("ETH-Bahnhof", 120);
  ASSERT_EQ(frames.size(), 120U);
  {
    BinaryFileSink sink(file("tracks.bin"));
    for (const auto& frame : frames) sink.write(frame);
    sink.flush();
  }
  MessageFileReader reader(file("tracks.bin"));
  std::vector<std::uint8_t> bytes;
  DecodedMessage decoded;
  for (const auto& frame : frames) {
    ASSERT_EQ(reader.next(bytes), FileReadStatus::message) << reader.problem();
    ASSERT_EQ(decode_message(bytes.data(), bytes.size(), decoded), DecodeError::none);
    ASSERT_TRUE(test::same_as_sent(frame, decoded));
  }
  EXPECT_EQ(reader.next(bytes), FileReadStatus::end_of_file);
  EXPECT_EQ(reader.records_read(), frames.size());
}

TEST_F(FileSinks, BinaryFileKeepsCrowdsWholeUnlikeUdp) {
  const FrameResult crowd = test::crowd_from_detections("ETH-Bahnhof", 200);
  { BinaryFileSink(file("crowd.bin")).write(crowd); }
  MessageFileReader reader(file("crowd.bin"));
  std::vector<std::uint8_t> bytes;
  DecodedMessage decoded;
  ASSERT_EQ(reader.next(bytes), FileReadStatus::message);
  ASSERT_EQ(decode_message(bytes.data(), bytes.size(), decoded), DecodeError::none);
  EXPECT_TRUE(test::same_as_sent(crowd, decoded));
}

TEST_F(FileSinks, CutOrCorruptFramingIsReportedWithItsRecord) {
  const auto frames = test::frames_from_detections("TUD-Campus", 10);
  {
    BinaryFileSink sink(file("cut.bin"));
    for (const auto& frame : frames) sink.write(frame);
  }
  const auto full_size = std::filesystem::file_size(file("cut.bin"));
  std::filesystem::resize_file(file("cut.bin"), full_size - 7);
  MessageFileReader cut(file("cut.bin"));
  std::vector<std::uint8_t> bytes;
  for (std::size_t i = 0; i + 1 < frames.size(); ++i)
    ASSERT_EQ(cut.next(bytes), FileReadStatus::message);
  EXPECT_EQ(cut.next(bytes), FileReadStatus::broken_framing);
  EXPECT_NE(cut.problem().find("record 10"), std::string::npos) << cut.problem();

  {
    std::ofstream huge(file("huge.bin"), std::ios::binary);
    huge.write("\xFF\xFF\xFF\x7F", 4);  // a 2 GiB length: must be refused before any allocation
  }
  MessageFileReader hostile(file("huge.bin"));
  EXPECT_EQ(hostile.next(bytes), FileReadStatus::broken_framing);
  EXPECT_NE(hostile.problem().find("above the maximum"), std::string::npos) << hostile.problem();
}

TEST_F(FileSinks, UnwritableFilesAreInputErrorsNamingThem) {
  const auto missing_dir = file("no-such-dir/tracks.bin");
  try {
    BinaryFileSink sink(missing_dir);
    FAIL() << "opened " << missing_dir;
  } catch (const InputError& error) {
    EXPECT_EQ(error.file(), missing_dir.string());
  }
  EXPECT_THROW(MessageFileReader(file("absent.bin")), InputError);
  if (std::filesystem::exists("/dev/full")) {
    // A full disk shows at the latest when the buffer is flushed.
    JsonlSink sink("/dev/full");
    const auto frames = test::frames_from_detections("ETH-Bahnhof", 100);
    EXPECT_THROW(
        {
          for (const auto& frame : frames) sink.write(frame);
          sink.flush();
        },
        InputError);
  }
}

TEST_F(FileSinks, JsonLinesParseBackToTheSameFrames) {
  auto frames = test::frames_from_detections("Venice-2", 60);
  ASSERT_EQ(frames.size(), 60U);
  ASSERT_FALSE(frames[3].tracks.empty());
  frames[3].tracks[0].score = std::numeric_limits<float>::infinity();  // JSON has no Inf: null
  // MOT15's detections are all pedestrians (class 1); a label map for them.
  const ClassLabelFn labels = [](int class_id) -> std::string_view {
    return class_id == 1 ? "person" : "";
  };
  const std::int64_t before_ns = wall_now_ns();
  {
    JsonlSink sink(file("tracks.jsonl"), labels);
    for (const auto& frame : frames) sink.write(frame);
  }
  const std::int64_t after_ns = wall_now_ns();
  std::ifstream in(file("tracks.jsonl"));
  std::string line;
  std::size_t index = 0;
  while (std::getline(in, line)) {
    ASSERT_LT(index, frames.size());
    const FrameResult& frame = frames[index++];
    const auto json = nlohmann::json::parse(line);  // throws, failing the test, if not JSON
    EXPECT_EQ(json.at("schema").get<int>(), json_schema_version);
    const auto wall_ns = json.at("wall_ns").get<std::int64_t>();
    EXPECT_GE(wall_ns, before_ns);
    EXPECT_LE(wall_ns, after_ns);
    // "time" is wall_ns in ISO 8601 UTC, to the millisecond.
    const std::time_t seconds = static_cast<std::time_t>(wall_ns / 1000000000);
    std::tm utc{};
    gmtime_r(&seconds, &utc);
    char expected[32];
    std::strftime(expected, sizeof expected, "%Y-%m-%dT%H:%M:%S", &utc);
    EXPECT_EQ(json.at("time").get<std::string>(),
              fmt::format("{}.{:03}Z", expected, (wall_ns / 1000000) % 1000));
    EXPECT_EQ(json.at("stream").get<std::uint32_t>(), frame.stream_id);
    EXPECT_EQ(json.at("sequence").get<std::uint64_t>(), frame.sequence);
    EXPECT_EQ(json.at("frame").get<std::int64_t>(), frame.frame_number);
    EXPECT_EQ(json.at("pts_ns").get<std::int64_t>(), frame.pts_ns);
    EXPECT_EQ(json.at("latency_ns").get<std::int64_t>(),
              frame.times.sent_ns - frame.times.captured_ns);
    EXPECT_EQ(json.at("frames_dropped").get<std::uint32_t>(), frame.frames_dropped);
    EXPECT_FALSE(json.at("truncated").get<bool>());
    const auto& tracks = json.at("tracks");
    ASSERT_EQ(tracks.size(), frame.tracks.size());
    for (std::size_t i = 0; i < tracks.size(); ++i) {
      const auto& track = frame.tracks[i];
      EXPECT_EQ(tracks[i].at("id").get<std::int32_t>(), track.id);
      EXPECT_EQ(tracks[i].at("class").get<std::int32_t>(), track.class_id);
      EXPECT_EQ(tracks[i].at("label").get<std::string>(), "person");
      // Shortest round-trip formatting: the float read back is the float written.
      EXPECT_EQ(tracks[i].at("x").get<float>(), track.box.x);
      EXPECT_EQ(tracks[i].at("y").get<float>(), track.box.y);
      EXPECT_EQ(tracks[i].at("w").get<float>(), track.box.w);
      EXPECT_EQ(tracks[i].at("h").get<float>(), track.box.h);
      if (std::isfinite(track.score)) {
        EXPECT_EQ(tracks[i].at("score").get<float>(), track.score);
      } else {
        EXPECT_TRUE(tracks[i].at("score").is_null());
      }
      EXPECT_EQ(tracks[i].at("hits").get<std::int32_t>(), track.hits);
      EXPECT_EQ(tracks[i].at("age").get<std::int32_t>(), track.age);
    }
  }
  EXPECT_EQ(index, frames.size());
}

}  // namespace
}  // namespace rtmot::messages
