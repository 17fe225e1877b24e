// Full-rate output (output.full_rate, docs/full-rate.md) through the real pipeline: a MOT15
// sequence (mot-seq://, replayed detections) in simulated playback behind a detector slower than
// the camera, run with the option off and on. On: one message per camera frame, those of skipped
// frames flagged predicted in the JSON lines and the binary messages alike; the processed frames'
// messages and MOTChallenge rows are the same as with the option off (the predictions never fed
// back into the tracker). And the recorded detections of such a run (output.mot_detections).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "messages/message_file_reader.hpp"
#include "messages/message_format.hpp"
#include "motio/mot_files.hpp"
#include "motio/processed_frames.hpp"
#include "pipeline/pipeline.hpp"
#include "pipeline_test_parts.hpp"
#include "runner/run_config.hpp"
#include "runner/run_setup.hpp"
#include "shared_data.hpp"
#include "tracker/tracker.hpp"

namespace rtmot::pipeline {
namespace {

namespace fs = std::filesystem;

struct RunFiles {
  std::vector<nlohmann::json> lines;             // JSON lines, in order
  std::vector<messages::DecodedMessage> binary;  // binary messages, in order
  std::vector<std::string> mot_rows;             // NAME.txt's lines
  std::vector<int> processed;                    // NAME.frames
};

std::vector<std::string> lines_of(const fs::path& file) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// The run a configuration describes, as `rtmot run` makes it, until its input ends; its outputs
// are whole when this returns.
void run_to_the_end(const runner::RunConfig& config) {
  runner::validate(config);
  auto inputs = runner::make_inputs(config);
  runner::RunOutputs outputs = runner::make_outputs(config, inputs);
  Pipeline pipeline(std::move(inputs), runner::make_detector(config), std::move(outputs.consumers),
                    runner::make_options(config));
  const std::atomic<bool> stop{false};
  pipeline.run(stop);
}

RunFiles run(const fs::path& sequence, double latency_ms, bool full_rate, const std::string& tag) {
  const fs::path out =
      fs::temp_directory_path() / ("rtmot-full-rate-" + std::to_string(::getpid()) + "-" + tag);
  fs::remove_all(out);
  fs::create_directories(out);
  runner::RunConfig config = runner::default_run_config();
  config.source.uri = "mot-seq://" + sequence.string();
  config.detector.kind = runner::DetectorKind::replay;
  config.detector.det_file = (sequence / "det/det.txt").string();
  config.playback.mode = PlaybackMode::simulated;
  config.playback.latency_ms = latency_ms;
  config.output.mot_results = (out / "mot").string();
  config.output.jsonl_file = (out / "tracks.jsonl").string();
  config.output.binary_file = (out / "tracks.bin").string();
  config.output.full_rate = full_rate;
  config.stats_interval_s = 0.0;
  run_to_the_end(config);
  RunFiles files;
  for (const std::string& line : lines_of(out / "tracks.jsonl"))
    files.lines.push_back(nlohmann::json::parse(line));
  messages::MessageFileReader reader(out / "tracks.bin");
  std::vector<std::uint8_t> bytes;
  while (reader.next(bytes) == messages::FileReadStatus::message) {
    messages::DecodedMessage message;
    EXPECT_EQ(messages::decode_message(bytes.data(), bytes.size(), message),
              messages::DecodeError::none);
    files.binary.push_back(message);
  }
  const motio::SequenceInfo info = motio::read_seqinfo(sequence / "seqinfo.ini");
  files.mot_rows = lines_of(out / "mot" / (info.name + ".txt"));
  files.processed =
      motio::read_processed_frames(out / "mot" / (info.name + ".frames"), info.length);
  fs::remove_all(out);
  return files;
}

// What must not change with the option: everything but the clocks and the message count.
nlohmann::json without_clocks(nlohmann::json line) {
  for (const char* field : {"time", "wall_ns", "captured_ns", "latency_ns", "sequence"})
    line.erase(field);
  return line;
}

int frame_of(const std::string& mot_row) {
  return std::stoi(mot_row.substr(0, mot_row.find(',')));
}

TEST(FullRate, OneMessagePerCameraFramePredictedFlaggedProcessedUnchanged) {
  const fs::path sequence = test::shared_path("data/mot15-train/TUD-Stadtmitte");
  RTMOT_REQUIRE_FILE(sequence / "det/det.txt");
  const motio::SequenceInfo info = motio::read_seqinfo(sequence / "seqinfo.ini");
  // 200 ms at 25 fps: the detector takes every 5th frame, 4 of 5 skipped.
  const RunFiles off = run(sequence, 200.0, false, "off");
  const RunFiles on = run(sequence, 200.0, true, "on");

  // The same frames processed either way, and far fewer than the camera's.
  ASSERT_EQ(on.processed, off.processed);
  ASSERT_LT(on.processed.size() * 4, static_cast<std::size_t>(info.length));
  const std::set<int> processed(on.processed.begin(), on.processed.end());

  // Off: one message per processed frame, none predicted.
  ASSERT_EQ(off.lines.size(), off.processed.size());
  for (const auto& line : off.lines) EXPECT_FALSE(line.contains("predicted"));

  // On: one message per camera frame 1..length, in order, sequence numbers without a gap; the
  // skipped ones flagged predicted, in the JSON lines and the binary messages alike.
  ASSERT_EQ(on.lines.size(), static_cast<std::size_t>(info.length));
  ASSERT_EQ(on.binary.size(), on.lines.size());
  std::size_t predicted_tracks = 0;
  std::set<int> last_processed_ids;
  for (std::size_t i = 0; i < on.lines.size(); ++i) {
    const auto& line = on.lines[i];
    const int frame = static_cast<int>(i) + 1;
    ASSERT_EQ(line.at("frame").get<int>(), frame);
    EXPECT_EQ(line.at("sequence").get<std::uint64_t>(), i);
    const bool skipped = processed.count(frame) == 0;
    EXPECT_EQ(line.value("predicted", false), skipped) << "frame " << frame;
    const messages::DecodedMessage& message = on.binary[i];
    EXPECT_EQ(message.frame.frame_number, frame);
    EXPECT_EQ(message.frame.predicted, skipped) << "frame " << frame;
    EXPECT_EQ((message.flags & messages::message::flag_predicted) != 0, skipped);
    EXPECT_EQ(message.frame.tracks.size(), line.at("tracks").size());
    std::set<int> ids;
    std::set<int> matched_twice;  // in a row: those predicted (tracker::kPredictedMinHits)
    for (const auto& track : line.at("tracks")) {
      ids.insert(track.at("id").get<int>());
      if (track.at("hits").get<int>() >= tracker::kPredictedMinHits)
        matched_twice.insert(track.at("id").get<int>());
    }
    if (skipped) {
      // The tracks the last processed frame reported matched twice in a row, and only those.
      EXPECT_EQ(ids, last_processed_ids) << "frame " << frame;
      predicted_tracks += ids.size();
      EXPECT_FALSE(line.contains("events"));
    } else {
      last_processed_ids = matched_twice;
    }
  }
  EXPECT_GT(predicted_tracks, 100U);

  // The processed frames' messages: as with the option off, but for the clocks and sequence.
  std::vector<nlohmann::json> processed_on;
  for (const auto& line : on.lines) {
    if (!line.value("predicted", false)) processed_on.push_back(without_clocks(line));
  }
  ASSERT_EQ(processed_on.size(), off.lines.size());
  for (std::size_t i = 0; i < off.lines.size(); ++i)
    EXPECT_EQ(processed_on[i].dump(), without_clocks(off.lines[i]).dump()) << "message " << i;

  // MOTChallenge rows: the processed frames' are byte for byte those of the run without the
  // option; the skipped frames have rows too.
  std::vector<std::string> processed_rows;
  std::set<int> row_frames;
  for (const std::string& row : on.mot_rows) {
    row_frames.insert(frame_of(row));
    if (processed.count(frame_of(row)) != 0) processed_rows.push_back(row);
  }
  EXPECT_EQ(processed_rows, off.mot_rows);
  EXPECT_GT(on.mot_rows.size(), off.mot_rows.size() * 3);
  EXPECT_GT(row_frames.size(), processed.size() * 3);
}

// A live camera three times faster than the detector: the latest-frame slot overwrites most
// frames before the detector takes one. Those frames still get their predicted message, from the
// trail the next published frame carries, so the output has one message per camera frame, in
// order. (A frame every millisecond: the trail's 128 frames leave a loaded machine 100 ms of
// stall.)
class PacedCamera : public test_parts::PatternSource {
 public:
  using PatternSource::PatternSource;
  platform::ReadStatus read(cv::Mat& bgr, platform::FrameInfo& info) override {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    return PatternSource::read(bgr, info);
  }
};

class SlowDetector : public test_parts::FixedBoxDetector {
 public:
  void detect(const cv::Mat& image, std::int64_t frame_number,
              std::vector<tracker::Detection>& out) override {
    std::this_thread::sleep_for(std::chrono::milliseconds(3));
    FixedBoxDetector::detect(image, frame_number, out);
  }
};

TEST(FullRate, ALiveSourceGetsAMessageForEveryFrameTheSlotDropped) {
  constexpr std::int64_t kFrames = 600;
  test_parts::Collected collected;
  PipelineOptions options = test_parts::quiet(PlaybackMode::realtime);
  options.full_rate = true;
  Pipeline pipeline(std::make_unique<PacedCamera>(kFrames), std::make_unique<SlowDetector>(),
                    test_parts::sort_for(1000.0), test_parts::sinks_into(collected), options);
  const std::atomic<bool> stop{false};
  pipeline.run(stop);
  const auto& results = collected.results;
  ASSERT_EQ(results.size(), static_cast<std::size_t>(kFrames));
  std::size_t predicted = 0;
  std::size_t predicted_tracks = 0;
  for (std::size_t i = 0; i < results.size(); ++i) {
    EXPECT_EQ(results[i].frame_number, static_cast<std::int64_t>(i) + 1);
    EXPECT_EQ(results[i].sequence, i);
    if (results[i].predicted) {
      ++predicted;
      predicted_tracks += results[i].tracks.size();
    }
  }
  // The slot dropped most frames, and the last one is always processed.
  EXPECT_GT(predicted, results.size() / 2);
  EXPECT_FALSE(results.back().predicted);
  EXPECT_GT(predicted_tracks, predicted);  // the two people, once confirmed
}

// output.mot_detections through the threaded pipeline behind a slow detector (full rate, so the
// predicted messages pass the consumer too): NAME.det.txt holds each processed frame's detections
// as the replay detector served them, the very floats, and nothing of the skipped frames; replayed
// in place of the sequence's det.txt, the run's results come back byte for byte.
TEST(FullRate, TheRecordedDetectionsAreTheProcessedFramesAndReplayTheRun) {
  const fs::path sequence = test::shared_path("data/mot15-train/TUD-Stadtmitte");
  RTMOT_REQUIRE_FILE(sequence / "det/det.txt");
  const motio::SequenceInfo info = motio::read_seqinfo(sequence / "seqinfo.ini");
  const fs::path out = fs::temp_directory_path() / ("rtmot-recorded-" + std::to_string(::getpid()));
  fs::remove_all(out);
  const auto run_with = [&](const fs::path& det_file, const std::string& tag) {
    runner::RunConfig config = runner::default_run_config();
    config.source.uri = "mot-seq://" + sequence.string();
    config.detector.kind = runner::DetectorKind::replay;
    config.detector.det_file = det_file.string();
    config.playback.mode = PlaybackMode::simulated;
    config.playback.latency_ms = 200.0;
    config.output.mot_results = (out / tag).string();
    config.output.mot_detections = true;
    config.output.full_rate = true;
    config.stats_interval_s = 0.0;
    run_to_the_end(config);
  };
  run_with(sequence / "det/det.txt", "live");
  const fs::path recorded = out / "live" / (info.name + ".det.txt");
  const std::vector<int> processed =
      motio::read_processed_frames(out / "live" / (info.name + ".frames"), info.length);
  ASSERT_LT(processed.size() * 4, static_cast<std::size_t>(info.length));  // most skipped

  // What the tracker got at each processed frame: the file's rows of that frame at or above the
  // detector's cut, in the file's order.
  const float threshold = runner::default_run_config().detector.score_threshold;
  const std::set<int> wanted(processed.begin(), processed.end());
  std::vector<motio::MotRow> expected;
  for (const auto& row :
       motio::read_mot_file(sequence / "det/det.txt", motio::MotFileKind::detections)) {
    if (wanted.count(row.frame) != 0 && row.conf >= threshold) expected.push_back(row);
  }
  const auto got = motio::read_mot_file(recorded, motio::MotFileKind::detections);
  ASSERT_EQ(got.size(), expected.size());
  ASSERT_GT(got.size(), 100U);
  for (std::size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i].frame, expected[i].frame) << "row " << i;
    EXPECT_EQ(got[i].box.x, expected[i].box.x) << "row " << i;
    EXPECT_EQ(got[i].box.y, expected[i].box.y) << "row " << i;
    EXPECT_EQ(got[i].box.w, expected[i].box.w) << "row " << i;
    EXPECT_EQ(got[i].box.h, expected[i].box.h) << "row " << i;
    EXPECT_EQ(got[i].conf, expected[i].conf) << "row " << i;
  }

  run_with(recorded, "replayed");
  EXPECT_EQ(lines_of(out / "replayed" / (info.name + ".txt")),
            lines_of(out / "live" / (info.name + ".txt")));
  EXPECT_EQ(lines_of(out / "replayed" / (info.name + ".det.txt")), lines_of(recorded));
  fs::remove_all(out);
}

}  // namespace
}  // namespace rtmot::pipeline
