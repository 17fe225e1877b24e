// Cold start, with rtmot itself as a child process: a live source (an RTSP camera) that is absent
// when the service starts is retried with the outage backoff: rtmot runs, sends source_outage
// messages, and tracks once the camera (an RTSP server started here, streaming vtest.avi) appears.
// A missing file and a malformed URI still fail at once.
#include <gst/gst.h>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "child_process.hpp"
#include "outputs/rtsp_video_server.hpp"
#include "platform/video_source.hpp"
#include "scratch_folder.hpp"
#include "shared_data.hpp"

namespace rtmot::outputs {
namespace {

using namespace std::chrono_literals;

class ColdStart : public ::testing::Test {
 protected:
  test::ScratchFolder scratch_{"cold"};  // removed when the test passed
  std::filesystem::path folder_ = scratch_.path();
  std::filesystem::path model_ = test::source_path("models/ssdlite_mobilenet_v2_coco.onnx");

  int run_to_end(const std::vector<std::string>& args) {
    std::vector<std::string> argv{RTMOT_BINARY};
    argv.insert(argv.end(), args.begin(), args.end());
    test::ChildProcess rtmot(argv, folder_ / "out.txt", folder_ / "err.txt");
    const int status = rtmot.wait(60s);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
};

TEST_F(ColdStart, AbsentCameraIsAnOutageUntilItAppears) {
  RTMOT_REQUIRE_FILE(model_);
  const auto video = test::shared_path("data/video/vtest.avi");
  RTMOT_REQUIRE_FILE(video);
  const unsigned short port = test::free_tcp_port();
  const std::string camera = "rtsp://127.0.0.1:" + std::to_string(port) + "/camera";
  const auto jsonl = folder_ / "tracks.jsonl";
  test::ChildProcess rtmot(
      {RTMOT_BINARY, "run", "--source", camera, "--model", model_.string(), "--jsonl",
       jsonl.string(), "--max-frames", "40", "--stats-interval", "0"},
      folder_ / "out.txt", folder_ / "err.txt");
  // Up and reporting the outage while nothing listens on the port: the source said so, and the
  // pipeline runs (its detectors are built: "in flight" is the last line before it starts; start-up
  // is slow under qemu and on a loaded machine, where the engines are measured for seconds).
  const auto deadline = std::chrono::steady_clock::now() + 60s;
  const auto started = [&] {
    const std::string err = test::read_text(folder_ / "err.txt");
    return err.find("retrying with backoff") != std::string::npos &&
           err.find(" in flight") != std::string::npos;
  };
  while (!started() && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(100ms);
  }
  std::this_thread::sleep_for(2s);  // a couple of seconds of outage ticks
  ASSERT_TRUE(rtmot.running());
  ASSERT_NE(test::read_text(folder_ / "err.txt").find("retrying with backoff"), std::string::npos)
      << test::read_text(folder_ / "err.txt");

  // The camera appears: vtest.avi's people at 10 fps, until rtmot has its 40 frames and ends.
  RtspVideoServer server(
      [&] {
        VideoTarget target;
        target.kind = VideoTargetKind::rtsp;
        target.text = camera;
        target.host = "127.0.0.1";
        target.port = port;
        target.mount = "/camera";
        return target;
      }(),
      10.0);
  std::atomic<bool> done{false};
  std::thread camera_thread([&] {
    auto source = platform::open_video_source(video.string());
    cv::Mat frame;
    platform::FrameInfo info;
    while (!done && source->read(frame, info) == platform::ReadStatus::frame) {
      server.push(frame);
      std::this_thread::sleep_for(100ms);
    }
  });
  const int status = rtmot.wait(90s);
  done = true;
  camera_thread.join();
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0)
      << status << "\n"
      << test::read_text(folder_ / "err.txt");

  std::ifstream lines(jsonl);
  std::string line;
  int outage = 0;
  int tracked = 0;
  int with_people = 0;
  bool outage_after_tracking = false;
  while (std::getline(lines, line)) {
    const auto json = nlohmann::json::parse(line);
    if (json.at("source_outage").get<bool>()) {
      ++outage;
      outage_after_tracking = outage_after_tracking || tracked > 0;
    } else {
      ++tracked;
      if (!json.at("tracks").empty()) ++with_people;
    }
  }
  EXPECT_GT(outage, 5);  // ticks while the camera was absent (about 10 a second)
  EXPECT_GT(tracked, 10);
  EXPECT_GT(with_people, 5);  // vtest.avi's pedestrians were tracked once it appeared
  EXPECT_FALSE(outage_after_tracking);
}

// Two cameras absent at start: each says so, and the operator also gets one line that no source
// delivers pictures; when one appears, one line that a source is back (issue 22).
TEST_F(ColdStart, EverySourceDownIsOneLineAndSoIsTheFirstBack) {
  RTMOT_REQUIRE_FILE(model_);
  const auto video = test::shared_path("data/video/vtest.avi");
  RTMOT_REQUIRE_FILE(video);
  const unsigned short port = test::free_tcp_port();
  const std::string camera = "rtsp://127.0.0.1:" + std::to_string(port) + "/camera";
  const std::string absent = "rtsp://127.0.0.1:" + std::to_string(test::free_tcp_port()) + "/never";
  test::ChildProcess rtmot(
      {RTMOT_BINARY, "run", "--source", camera, "--source", absent, "--model", model_.string(),
       "--jsonl", (folder_ / "t.jsonl").string(), "--stats-interval", "0"},
      folder_ / "out.txt", folder_ / "err.txt");
  const auto wait_for = [&](const std::string& text) {
    const auto deadline = std::chrono::steady_clock::now() + 60s;
    while (test::read_text(folder_ / "err.txt").find(text) == std::string::npos &&
           std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(100ms);
    }
    return test::read_text(folder_ / "err.txt").find(text) != std::string::npos;
  };
  ASSERT_TRUE(wait_for("all 2 sources are down")) << test::read_text(folder_ / "err.txt");
  RtspVideoServer server(
      [&] {
        VideoTarget target;
        target.kind = VideoTargetKind::rtsp;
        target.text = camera;
        target.host = "127.0.0.1";
        target.port = port;
        target.mount = "/camera";
        return target;
      }(),
      10.0);
  std::atomic<bool> done{false};
  std::thread camera_thread([&] {
    auto source = platform::open_video_source(video.string());
    cv::Mat frame;
    platform::FrameInfo info;
    while (!done && source->read(frame, info) == platform::ReadStatus::frame) {
      server.push(frame);
      std::this_thread::sleep_for(100ms);
    }
  });
  const bool back = wait_for("a source is back after all 2 were down");
  const int status = rtmot.stop(SIGINT, 30s);
  done = true;
  camera_thread.join();
  const std::string err = test::read_text(folder_ / "err.txt");
  EXPECT_TRUE(back) << err;
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status << "\n" << err;
  // Once per episode, whichever capture thread saw it.
  EXPECT_EQ(err.find("all 2 sources are down"), err.rfind("all 2 sources are down")) << err;
}

TEST_F(ColdStart, MissingFileAndMalformedUriFailAtOnce) {
  EXPECT_EQ(run_to_end(
                {"run", "--source", (folder_ / "absent.avi").string(), "--model", model_.string()}),
            5);
  EXPECT_EQ(run_to_end({"run", "--source", "rtsp://127.0.0.1:99999/x", "--model", model_.string()}),
            5);
  const std::string err = test::read_text(folder_ / "err.txt");
  EXPECT_EQ(err.find("retrying"), std::string::npos) << err;
}

// A live URI whose GStreamer element is missing (csi:// off a Jetson: no nvarguscamerasrc) is not a
// camera that boots late: exit 5 at once, naming the element and where it comes from (it was
// retried for ever). A v4l2 device that is absent is still a cold start (the test above).
TEST_F(ColdStart, MissingGStreamerElementFailsAtOnce) {
  gst_init(nullptr, nullptr);
  if (GstElementFactory* factory = gst_element_factory_find("nvarguscamerasrc")) {
    gst_object_unref(factory);
    GTEST_SKIP() << "this machine has nvarguscamerasrc (a Jetson): csi://0 may be a cold start";
  }
  EXPECT_EQ(run_to_end({"run", "--source", "csi://0", "--model", model_.string()}), 5);
  const std::string err = test::read_text(folder_ / "err.txt");
  EXPECT_NE(err.find("no element \"nvarguscamerasrc\""), std::string::npos) << err;
  EXPECT_NE(err.find("L4T"), std::string::npos) << err;
  EXPECT_EQ(err.find("retrying"), std::string::npos) << err;
}

}  // namespace
}  // namespace rtmot::outputs

namespace rtmot::outputs {
namespace {

// The systemd unit matches the cold start: it never stops restarting (no start limit), and it
// does not treat exit 5 (source failed) as final.
TEST(ColdStartUnit, ServiceNeverGivesUp) {
  const std::string unit = test::read_text(test::source_path("scripts/deploy/rtmot.service.in"));
  ASSERT_FALSE(unit.empty());
  EXPECT_NE(unit.find("\nStartLimitIntervalSec=0\n"), std::string::npos);
  EXPECT_NE(unit.find("\nRestart=on-failure\n"), std::string::npos);
  const auto prevent = unit.find("\nRestartPreventExitStatus=");
  ASSERT_NE(prevent, std::string::npos);
  const std::string codes = unit.substr(prevent, unit.find('\n', prevent + 1) - prevent);
  EXPECT_EQ(codes.find('5'), std::string::npos) << codes;
}

}  // namespace
}  // namespace rtmot::outputs
