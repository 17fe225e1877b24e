// The README's demo as a test: `rtmot run` on vtest.avi with the real SSD in realtime playback
// (the detector skips frames) and `--video-out` into a folder that does not exist. The MP4 is read
// back by GStreamer: H.264, index first, every source frame; one frame saved as PNG and checked for
// the overlay. And an unwritable target: one error line, before the model loads.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "child_process.hpp"
#include "gst_read_back.hpp"
#include "scratch_folder.hpp"
#include "shared_data.hpp"

namespace rtmot::outputs {
namespace {

using namespace std::chrono_literals;

constexpr int frames = 150;

class RunVideo : public ::testing::Test {
 protected:
  test::ScratchFolder scratch_{"run-video"};  // removed when the test passed
  std::filesystem::path folder_ = scratch_.path();
  std::filesystem::path model_ = test::source_path("models/ssdlite_mobilenet_v2_coco.onnx");
  std::filesystem::path video_ = test::shared_path("data/video/vtest.avi");
};

TEST_F(RunVideo, DemoWritesEverySourceFrameAsBrowserPlayableH264) {
  RTMOT_REQUIRE_FILE(model_);
  RTMOT_REQUIRE_FILE(video_);
  const auto mp4 = folder_ / "out/demo.mp4";  // out/ does not exist yet
  const auto jsonl = folder_ / "tracks.jsonl";
  test::ChildProcess rtmot(
      {RTMOT_BINARY, "run", "--source", video_.string(), "--model", model_.string(), "--playback",
       "simulated", "--latency-ms", "250", "--max-frames", std::to_string(frames), "--jsonl",
       jsonl.string(), "--video-out", mp4.string()},
      folder_ / "out.txt", folder_ / "err.txt");
  const int status = rtmot.wait(300s);
  const std::string err = test::read_text(folder_ / "err.txt");
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status << "\n" << err;
  EXPECT_NE(err.find("output: video -> " + mp4.string()), std::string::npos) << err;
  EXPECT_EQ(err.find("source frames are missing"), std::string::npos) << err;

  // The detector (simulated at 250 ms on a 10 fps file) processed only some frames...
  std::ifstream lines(jsonl);
  int processed = 0;
  for (std::string line; std::getline(lines, line);) ++processed;
  EXPECT_GT(processed, 20);
  EXPECT_LT(processed, frames / 2);
  // ...and the video still has every source frame.
  const test::ReadBack back =
      test::read_back("filesrc location=" + mp4.string() +
                          " ! qtdemux ! video/x-h264 ! avdec_h264" + test::to_bgr_sink,
                      100, 100000, 120s);
  EXPECT_EQ(back.frames, frames);
  std::ifstream file(mp4, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  EXPECT_NE(bytes.find("avc1"), std::string::npos);
  EXPECT_LT(bytes.find("moov"), bytes.find("mdat"));  // faststart: plays while downloading
  // Frame 101 as a PNG: vtest.avi's size, and the stats line's dark band at the top left.
  ASSERT_FALSE(back.saved.empty());
  const auto png = folder_ / "frame101.png";
  ASSERT_TRUE(cv::imwrite(png.string(), back.saved));
  const cv::Mat reread = cv::imread(png.string());
  ASSERT_EQ(reread.size(), cv::Size(768, 576));
  const cv::Vec3b band = reread.at<cv::Vec3b>(8, 20);
  EXPECT_LT(band[0] + band[1] + band[2], 3 * 90) << "no stats band: " << band;
}

// Full-rate output (docs/full-rate.md) with the video: one JSON line per source frame, the skipped
// ones predicted, and the video still every source frame (the skipped ones drawn from the
// predicted results).
TEST_F(RunVideo, FullRateOutputSendsEveryFrameAndTheVideoHasThemAll) {
  RTMOT_REQUIRE_FILE(model_);
  RTMOT_REQUIRE_FILE(video_);
  constexpr int kFrames = 60;
  const auto mp4 = folder_ / "full-rate.mp4";
  const auto jsonl = folder_ / "tracks.jsonl";
  test::ChildProcess rtmot(
      {RTMOT_BINARY, "run", "--source", video_.string(), "--model", model_.string(), "--playback",
       "simulated", "--latency-ms", "250", "--max-frames", std::to_string(kFrames), "--jsonl",
       jsonl.string(), "--video-out", mp4.string(), "--full-rate", "true"},
      folder_ / "out.txt", folder_ / "err.txt");
  const int status = rtmot.wait(300s);
  const std::string err = test::read_text(folder_ / "err.txt");
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status << "\n" << err;
  std::ifstream lines(jsonl);
  int messages = 0;
  int predicted = 0;
  for (std::string line; std::getline(lines, line);) {
    const auto json = nlohmann::json::parse(line);
    EXPECT_EQ(json.at("frame").get<int>(), ++messages);
    if (json.value("predicted", false)) ++predicted;
  }
  EXPECT_EQ(messages, kFrames);
  EXPECT_GT(predicted, kFrames / 2);  // 250 ms on a 10 fps file: 6 of 10 frames skipped
  const test::ReadBack back =
      test::read_back("filesrc location=" + mp4.string() +
                          " ! qtdemux ! video/x-h264 ! avdec_h264" + test::to_bgr_sink,
                      30, 100000, 120s);
  EXPECT_EQ(back.frames, kFrames);
}

TEST_F(RunVideo, UnwritableTargetIsOneErrorLineBeforeTheModelLoads) {
  std::filesystem::create_directories(folder_ / "dir.mp4");
  test::ChildProcess rtmot(
      {RTMOT_BINARY, "run", "--source", video_.string(), "--model",
       (folder_ / "no-model.onnx").string(), "--video-out", (folder_ / "dir.mp4").string()},
      folder_ / "out.txt", folder_ / "err.txt");
  const int status = rtmot.wait(60s);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 3);  // not 4: the missing model was never reached
  const std::string err = test::read_text(folder_ / "err.txt");
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  EXPECT_NE(err.find("dir.mp4"), std::string::npos) << err;
  EXPECT_NE(err.find("is a directory"), std::string::npos) << err;
}

}  // namespace
}  // namespace rtmot::outputs
