// `output.mot_results`: which name each source's results get, and the consumer's two files.
#include "runner/mot_results_output.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "common/input_error.hpp"
#include "motio/mot_files.hpp"
#include "motio/processed_frames.hpp"
#include "shared_data.hpp"

namespace rtmot::runner {
namespace {

namespace fs = std::filesystem;

class MotResultsOutputTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("rtmot-mot-results-" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  static std::string read(const fs::path& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }

  fs::path dir_;
};

SourceConfig source(const std::string& uri) {
  SourceConfig config;
  config.uri = uri;
  return config;
}

TEST_F(MotResultsOutputTest, NamesFollowTheSource) {
  const fs::path sequence = test::shared_path("data/mot15-train/TUD-Campus");
  RTMOT_REQUIRE_FILE(sequence / "seqinfo.ini");
  EXPECT_EQ(mot_results_name(source("mot-seq://" + sequence.string()), 0), "TUD-Campus");
  // An image folder in the MOTChallenge layout: SEQ/img1 and SEQ itself name the sequence.
  fs::create_directories(dir_ / "MySeq" / "img1");
  std::ofstream(dir_ / "MySeq" / "seqinfo.ini")
      << "[Sequence]\nname=My-Seq\nframeRate=10\nseqLength=3\nimWidth=64\nimHeight=48\n";
  EXPECT_EQ(mot_results_name(source("images://" + (dir_ / "MySeq/img1").string() + "?fps=10"), 0),
            "My-Seq");
  EXPECT_EQ(mot_results_name(source((dir_ / "MySeq/img1/").string()), 0), "My-Seq");
  // Without a seqinfo.ini: the folder's or file's own name, made plain.
  fs::create_directories(dir_ / "frames of day 2");
  EXPECT_EQ(mot_results_name(source((dir_ / "frames of day 2").string()), 0), "frames_of_day_2");
  EXPECT_EQ(mot_results_name(source("/videos/.hidden cam.mp4"), 0), "_hidden_cam");
  EXPECT_EQ(mot_results_name(source("file:///videos/yard%20east.avi"), 0), "yard_east");
  // Cameras and streams: the stream id.
  EXPECT_EQ(mot_results_name(source("rtsp://cam1/stream"), 7), "stream-7");
  EXPECT_EQ(mot_results_name(source("v4l2:///dev/video0"), 0), "stream-0");
  EXPECT_EQ(mot_results_name(source("test://ball?is-live=true"), 3), "stream-3");
}

TEST_F(MotResultsOutputTest, TwoSourcesWithOneNameAreRefused) {
  RunConfig config;
  config.sources = {source("/a/yard.mp4"), source("/b/yard.mp4")};
  try {
    mot_results_targets(config);
    FAIL() << "accepted two sources named yard";
  } catch (const InputError& error) {
    EXPECT_EQ(error.field(), "output.mot_results");
    EXPECT_NE(error.problem().find("'yard'"), std::string::npos) << error.what();
  }
  config.sources = {source("/a/yard.mp4"), source("rtsp://cam/x")};
  config.stream_id = 10;
  const auto targets = mot_results_targets(config);
  ASSERT_EQ(targets.size(), 2U);
  EXPECT_EQ(targets[1].name, "stream-11");
  EXPECT_EQ(targets[1].stream_id, 11U);
}

messages::FrameResult frame(std::uint32_t stream, std::int64_t number, int tracks) {
  messages::FrameResult result;
  result.stream_id = stream;
  result.frame_number = number;
  for (int i = 1; i <= tracks; ++i) {
    tracker::TrackReport report;
    report.id = i;
    report.box = {10.F * static_cast<float>(i), 20.F, 30.F, 60.F};
    report.score = 0.75F;
    result.tracks.push_back(report);
  }
  return result;
}

TEST_F(MotResultsOutputTest, WritesEachStreamsRowsAndFramesAtFinish) {
  const fs::path out = dir_ / "new" / "results";  // created
  MotResultsOutput output(out, {{4, "first"}, {5, "second"}});
  cv::Mat no_image;
  const std::vector<tracker::Detection> none;
  const auto consume = [&](const messages::FrameResult& result) {
    output.consume(pipeline::SinkFrame{result, no_image, 0.0, none});
  };
  consume(frame(4, 1, 2));
  consume(frame(5, 1, 0));
  consume(frame(4, 3, 1));  // frame 2 skipped
  messages::FrameResult outage = frame(4, 3, 0);
  outage.source_outage = true;  // a tick, not a processed frame
  consume(outage);
  consume(frame(9, 4, 1));  // no such stream
  // Nothing is published before finish().
  EXPECT_FALSE(fs::exists(out / "first.txt"));
  output.finish();
  EXPECT_EQ(read(out / "first.txt"),
            "1,1,10.00,20.00,30.00,60.00,0.7500,-1,-1,-1\n"
            "1,2,20.00,20.00,30.00,60.00,0.7500,-1,-1,-1\n"
            "3,1,10.00,20.00,30.00,60.00,0.7500,-1,-1,-1\n");
  EXPECT_EQ(motio::read_processed_frames(out / "first.frames", 10), (std::vector<int>{1, 3}));
  EXPECT_EQ(read(out / "second.txt"), "");
  EXPECT_EQ(motio::read_processed_frames(out / "second.frames", 10), (std::vector<int>{1}));
  // What eval reads back.
  EXPECT_EQ(motio::read_mot_file(out / "first.txt", motio::MotFileKind::results).size(), 3U);
  std::vector<fs::path> left;
  for (const auto& entry : fs::directory_iterator(out)) left.push_back(entry.path().filename());
  EXPECT_EQ(left.size(), 4U) << "a temporary left behind";
}

// output.mot_detections: the processed frames' detections as a det.txt that the replay detector
// and rtmot track read back; predicted frames and ticks add none.
TEST_F(MotResultsOutputTest, WritesTheProcessedFramesDetectionsAsADetFile) {
  const fs::path out = dir_ / "with-detections";
  MotResultsOutput output(out, {{4, "seq"}}, true);
  cv::Mat no_image;
  const std::vector<tracker::Detection> two = {
      tracker::Detection(tracker::Box{12.5F, 40.F, 30.25F, 80.F}, 0.91234F, 1),
      tracker::Detection(tracker::Box{300.F, 41.F, 28.F, 75.5F}, 0.3F, 1)};
  const std::vector<tracker::Detection> one = {
      tracker::Detection(tracker::Box{14.F, 40.F, 30.F, 80.F}, 0.88F, 1)};
  const auto consume = [&](const messages::FrameResult& result,
                           const std::vector<tracker::Detection>& detections) {
    output.consume(pipeline::SinkFrame{result, no_image, 0.0, detections});
  };
  consume(frame(4, 1, 1), two);
  messages::FrameResult predicted = frame(4, 2, 1);
  predicted.predicted = true;  // a skipped frame: no detections of its own
  consume(predicted, one);
  consume(frame(4, 3, 1), one);
  messages::FrameResult outage = frame(4, 4, 0);
  outage.source_outage = true;
  consume(outage, one);
  EXPECT_FALSE(fs::exists(out / "seq.det.txt"));  // whole at finish only
  output.finish();
  EXPECT_EQ(read(out / "seq.det.txt"),
            "1,-1,12.5,40,30.25,80,0.91234,-1,-1,-1\n"
            "1,-1,300,41,28,75.5,0.3,-1,-1,-1\n"
            "3,-1,14,40,30,80,0.88,-1,-1,-1\n");
  const auto rows = motio::read_mot_file(out / "seq.det.txt", motio::MotFileKind::detections);
  ASSERT_EQ(rows.size(), 3U);
  EXPECT_EQ(rows[2].frame, 3);
  // Read back as the very floats recorded (the replay's tracks are then the recorded run's).
  EXPECT_EQ(rows[0].box.w, 30.25F);
  EXPECT_EQ(rows[0].conf, 0.91234F);
  EXPECT_EQ(motio::read_processed_frames(out / "seq.frames", 10), (std::vector<int>{1, 3}));
}

TEST_F(MotResultsOutputTest, AFolderThatCannotBeMadeIsNamed) {
  std::ofstream(dir_ / "file") << "x";
  try {
    MotResultsOutput output(dir_ / "file" / "results", {{0, "s"}});
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_EQ(error.field(), "output.mot_results");
    EXPECT_NE(error.file().find("file/results"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace rtmot::runner
