#include <gst/gst.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <thread>

#include "common/input_error.hpp"
#include "platform/clock.hpp"
#include "platform/video_source.hpp"
#include "shared_data.hpp"

namespace rtmot::platform {
namespace {

using rtmot::test::shared_path;

constexpr std::int64_t ms = 1'000'000;

/// Expects open_video_source(uri) to throw InputError(source_failed) whose message contains
/// `words`.
void expect_open_fails(const std::string& uri, const std::string& words,
                       const SourceOptions& options = {}) {
  try {
    open_video_source(uri, options);
    ADD_FAILURE() << "opened " << uri;
  } catch (const InputError& error) {
    EXPECT_EQ(error.exit_code(), ExitCode::source_failed) << error.what();
    EXPECT_NE(std::string(error.what()).find(words), std::string::npos) << error.what();
  }
}

// ThreadSanitizer makes GStreamer's decoding several times slower, so under it the file test checks
// the first 100 frames and then destroys the source mid-stream (which exercises tearing down a
// running decoder); other builds check all 795.
#if defined(__SANITIZE_THREAD__)
constexpr std::int64_t vtest_frames_to_check = 100;
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
constexpr std::int64_t vtest_frames_to_check = 100;
#else
constexpr std::int64_t vtest_frames_to_check = 795;
#endif
#else
constexpr std::int64_t vtest_frames_to_check = 795;
#endif

TEST(FileSource, ReadsEveryFrameOfVtestWithTimestamps) {
  const auto path = shared_path("data/video/vtest.avi");
  RTMOT_REQUIRE_FILE(path);
  const auto source = open_video_source("file://" + path.string());
  EXPECT_EQ(source->info().width, 768);
  EXPECT_EQ(source->info().height, 576);
  EXPECT_DOUBLE_EQ(source->info().fps, 10.0);
  EXPECT_FALSE(source->info().live);

  cv::Mat frame;
  FrameInfo info;
  std::int64_t frames = 0;
  std::int64_t previous_capture_ns = 0;
  const uchar* buffer = nullptr;
  while (frames < vtest_frames_to_check && source->read(frame, info) == ReadStatus::frame) {
    ++frames;
    ASSERT_EQ(info.frame_number, frames);
    ASSERT_EQ(info.pts_ns, (frames - 1) * 100 * ms) << "frame " << frames;
    ASSERT_GE(info.capture_ns, previous_capture_ns);
    previous_capture_ns = info.capture_ns;
    ASSERT_EQ(frame.cols, 768);
    ASSERT_EQ(frame.rows, 576);
    ASSERT_EQ(frame.type(), CV_8UC3);
    if (frames == 1) buffer = frame.data;
    ASSERT_EQ(frame.data, buffer) << "the frame buffer was reallocated at frame " << frames;
  }
  ASSERT_EQ(frames, vtest_frames_to_check);
  if (vtest_frames_to_check == 795) {
    EXPECT_EQ(source->read(frame, info), ReadStatus::end_of_stream) << source->last_error();
  }
  // People walk through the scene: the last frame is a real picture, not a blank buffer.
  cv::Scalar mean, stddev;
  cv::meanStdDev(frame, mean, stddev);
  EXPECT_GT(stddev[0], 10.0);
}

// A multipart MJPEG file carries neither timestamps nor a frame rate. Its frames used to come out
// all at pts 0, so a realtime run released them at once and kept 3 of 30 without a word; they are
// now timed at an assumed rate (30 fps, or the configured one), with a warning.
TEST(FileSource, FramesWithoutTimestampsAreTimedAtARate) {
  const auto path = std::filesystem::temp_directory_path() /
                    ("rtmot-untimed-" + std::to_string(::getpid()) + ".mjpg");
  gst_init(nullptr, nullptr);
  GError* error = nullptr;
  GstElement* writer = gst_parse_launch(
      ("videotestsrc num-buffers=30 pattern=ball ! video/x-raw,width=160,height=120 ! jpegenc ! "
       "multipartmux ! filesink location=" +
       path.string())
          .c_str(),
      &error);
  ASSERT_NE(writer, nullptr) << (error != nullptr ? error->message : "gst_parse_launch");
  gst_element_set_state(writer, GST_STATE_PLAYING);
  GstBus* bus = gst_element_get_bus(writer);
  GstMessage* done = gst_bus_timed_pop_filtered(
      bus, 30 * GST_SECOND, static_cast<GstMessageType>(GST_MESSAGE_EOS | GST_MESSAGE_ERROR));
  ASSERT_NE(done, nullptr);
  EXPECT_EQ(GST_MESSAGE_TYPE(done), GST_MESSAGE_EOS);
  gst_message_unref(done);
  gst_object_unref(bus);
  gst_element_set_state(writer, GST_STATE_NULL);
  gst_object_unref(writer);

  for (const double configured : {0.0, 12.5}) {
    SourceOptions options;
    options.fps = configured;
    const auto source = open_video_source(path.string(), options);
    const double expected_fps = configured > 0.0 ? configured : 30.0;
    cv::Mat frame;
    FrameInfo info;
    std::int64_t frames = 0;
    while (source->read(frame, info) == ReadStatus::frame) {
      ++frames;
      EXPECT_EQ(info.pts_ns, std::llround((frames - 1) * 1e9 / expected_fps)) << "frame " << frames;
    }
    EXPECT_EQ(frames, 30);
  }
  std::filesystem::remove(path);
}

// vtest.avi is PETS09-S2L1, filmed at 7 fps while its header says 10. Re-timed, frame i plays at
// i / 7 s, and the source says 7 fps (so the tracker's clock and a simulated latency follow it);
// the file's length in frames is still read on the file's own clock.
TEST(FileSource, ARecordingWithAWrongRateIsReTimedByItsUri) {
  const auto path = shared_path("data/video/vtest.avi");
  RTMOT_REQUIRE_FILE(path);
  const auto source = open_video_source("file://" + path.string() + "?fps=7");
  EXPECT_DOUBLE_EQ(source->info().fps, 7.0);
  EXPECT_EQ(source->info().frame_count, 795);
  cv::Mat frame;
  FrameInfo info;
  for (std::int64_t frame_number = 1; frame_number <= 15; ++frame_number) {
    ASSERT_EQ(source->read(frame, info), ReadStatus::frame) << source->last_error();
    ASSERT_EQ(info.frame_number, frame_number);
    ASSERT_EQ(info.pts_ns, std::llround((frame_number - 1) * 1e9 / 7.0))
        << "frame " << frame_number;
  }
}

// A plain path is taken literally: "?fps=7" after one is part of the name, and the error says
// which form takes parameters.
TEST(FileSource, APlainPathWithAQuerySaysParametersNeedAFileUri) {
  const auto path = shared_path("data/video/vtest.avi");
  RTMOT_REQUIRE_FILE(path);
  try {
    open_video_source(path.string() + "?fps=7");
    ADD_FAILURE() << "opened " << path << "?fps=7";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("need a file:// URI"), std::string::npos)
        << error.what();
  }
}

TEST(FileSource, PlainPathOpensTheSameVideo) {
  const auto path = shared_path("data/video/vtest.avi");
  RTMOT_REQUIRE_FILE(path);
  const auto source = open_video_source(path.string());
  cv::Mat frame;
  FrameInfo info;
  ASSERT_EQ(source->read(frame, info), ReadStatus::frame) << source->last_error();
  EXPECT_EQ(info.frame_number, 1);
  EXPECT_EQ(frame.size(), cv::Size(768, 576));
}

TEST(FileSource, MissingFileFailsToOpen) {
  expect_open_fails("file:///nonexistent/dir/clip.avi", "/nonexistent/dir/clip.avi");
}

TEST(FileSource, NonVideoFileFailsToOpen) {
  const auto path = std::filesystem::temp_directory_path() / "rtmot-not-a-video.avi";
  {
    std::ofstream text(path);
    for (int i = 0; i < 200; ++i) text << "frame,id,x,y,w,h\n";
  }
  expect_open_fails(path.string(), path.string());
  std::filesystem::remove(path);
}

// Without its decoder (rank NONE hides it from decodebin, as if gstreamer1.0-libav were not
// installed) vtest.avi cannot be decoded: the open fails and says which decoder is missing.
TEST(FileSource, MissingDecoderFailsToOpenNamingIt) {
  const auto path = shared_path("data/video/vtest.avi");
  RTMOT_REQUIRE_FILE(path);
  gst_init(nullptr, nullptr);  // to reach the registry; the library's own init is then a no-op
  GstPluginFeature* decoder = gst_registry_lookup_feature(gst_registry_get(), "avdec_msmpeg4");
  ASSERT_NE(decoder, nullptr) << "gstreamer1.0-libav's avdec_msmpeg4 is not installed";
  const guint rank = gst_plugin_feature_get_rank(decoder);
  gst_plugin_feature_set_rank(decoder, GST_RANK_NONE);
  expect_open_fails(path.string(), "MPEG-4");
  gst_plugin_feature_set_rank(decoder, rank);
  gst_object_unref(decoder);
}

TEST(CameraSource, MissingV4l2DeviceFailsToOpen) {
  expect_open_fails("v4l2:///dev/rtmot-no-such-camera", "v4l2:///dev/rtmot-no-such-camera");
}

TEST(CameraSource, CsiWithoutNvidiaPluginsFailsToOpenNamingThem) {
  gst_init(nullptr, nullptr);
  if (gst_registry_check_feature_version(gst_registry_get(), "nvarguscamerasrc", 0, 0, 0)) {
    GTEST_SKIP() << "this machine has nvarguscamerasrc (a Jetson): the failure cannot be shown";
  }
  expect_open_fails("csi://0", "nvarguscamerasrc");
}

TEST(StreamSource, RefusedRtspConnectionFailsToOpen) {
  SourceOptions options;
  options.open_timeout_ms = 3000;
  // Port 1 on the loopback: nothing listens, the connection is refused at once.
  expect_open_fails("rtsp://127.0.0.1:1/stream", "rtsp://127.0.0.1:1/stream", options);
}

TEST(TestSource, DeliversFramesOfTheRequestedSizeThenEnds) {
  const auto source = open_video_source("test://ball?width=64&height=48&fps=25&num-buffers=5");
  EXPECT_EQ(source->info().width, 64);
  EXPECT_EQ(source->info().height, 48);
  EXPECT_DOUBLE_EQ(source->info().fps, 25.0);
  cv::Mat frame;
  FrameInfo info;
  for (int n = 1; n <= 5; ++n) {
    ASSERT_EQ(source->read(frame, info), ReadStatus::frame) << source->last_error();
    EXPECT_EQ(info.frame_number, n);
    EXPECT_EQ(info.pts_ns, (n - 1) * 40 * ms);
    EXPECT_EQ(frame.size(), cv::Size(64, 48));
  }
  EXPECT_EQ(source->read(frame, info), ReadStatus::end_of_stream);
  EXPECT_EQ(source->read(frame, info), ReadStatus::end_of_stream);
}

/// Reads until something other than a frame; returns it and how many frames came first.
std::pair<ReadStatus, int> read_to_end(VideoSource& source) {
  cv::Mat frame;
  FrameInfo info;
  int frames = 0;
  ReadStatus status;
  while ((status = source.read(frame, info)) == ReadStatus::frame) ++frames;
  return {status, frames};
}

TEST(TestSource, ErrorAfterNFrames) {
  const auto source = open_video_source("test://?width=32&height=32&error-after=3");
  const auto [status, frames] = read_to_end(*source);
  EXPECT_EQ(status, ReadStatus::error);
  EXPECT_EQ(frames, 3);
  EXPECT_FALSE(source->last_error().empty());
  cv::Mat frame;
  FrameInfo info;
  EXPECT_EQ(source->read(frame, info), ReadStatus::error) << "an error is final";
}

TEST(TestSource, EndOfStreamAfterNFrames) {
  const auto source = open_video_source("test://?width=32&height=32&eos-after=4&num-buffers=9");
  const auto [status, frames] = read_to_end(*source);
  EXPECT_EQ(status, ReadStatus::end_of_stream);
  EXPECT_EQ(frames, 4);
}

TEST(TestSource, ErrorBeforeTheFirstFrameFailsToOpen) {
  expect_open_fails("test://?error-after=0", "test://?error-after=0");
}

TEST(TestSource, UnknownPatternFailsToOpen) {
  expect_open_fails("test://plaid", "plaid");
}

TEST(TestSource, ShortStallDelaysButLosesNothing) {
  SourceOptions options;
  options.read_timeout_ms = 5000;
  const std::int64_t opened_ns = steady_now_ns();
  const auto source = open_video_source(
      "test://?width=32&height=32&num-buffers=4&stall-after=2&stall-ms=300", options);
  cv::Mat frame;
  std::vector<FrameInfo> infos(4);
  for (auto& info : infos) ASSERT_EQ(source->read(frame, info), ReadStatus::frame);
  EXPECT_EQ(infos[3].frame_number, 4);
  // The whole stall lies after the open began, and the third frame cannot exist before it ended.
  // (Not measured from the second frame's pull: that pull may itself happen during the stall.)
  EXPECT_GE(infos[2].capture_ns - opened_ns, 300 * ms);
  EXPECT_EQ(read_to_end(*source).first, ReadStatus::end_of_stream);
}

TEST(LiveTestSource, StallLongerThanTheReadTimeoutIsAnError) {
  SourceOptions options;
  options.read_timeout_ms = 200;
  const auto source = open_video_source(
      "test://?width=32&height=32&is-live=true&stall-after=1&stall-ms=60000", options);
  const auto [status, frames] = read_to_end(*source);
  EXPECT_EQ(status, ReadStatus::error);
  EXPECT_EQ(frames, 1);
  EXPECT_NE(source->last_error().find("200 ms"), std::string::npos) << source->last_error();
  // Destroying the source ends the stall rather than waiting out its minute.
}

TEST(TestSource, StallBeforeTheFirstFrameTimesOutTheOpen) {
  SourceOptions options;
  options.open_timeout_ms = 200;
  expect_open_fails("test://?stall-after=0&stall-ms=60000", "200 ms", options);
}

TEST(LiveTestSource, HandsOverTheNewestFrameAndCountsTheDroppedOnes) {
  const auto source = open_video_source("test://?width=32&height=32&fps=100&is-live=true");
  EXPECT_TRUE(source->info().live);
  cv::Mat frame;
  FrameInfo info;
  std::int64_t previous = 0;
  std::int64_t first = 0;
  constexpr int reads = 5;
  for (int n = 0; n < reads; ++n) {
    ASSERT_EQ(source->read(frame, info), ReadStatus::frame) << source->last_error();
    if (n == 0) first = info.frame_number;
    EXPECT_GT(info.frame_number, previous);
    // The frame number counts produced frames: it matches the source's clock.
    EXPECT_EQ(info.pts_ns, (info.frame_number - 1) * 10 * ms);
    previous = info.frame_number;
    std::this_thread::sleep_for(std::chrono::milliseconds(60));
  }
  EXPECT_EQ(first, 1);
  EXPECT_GT(previous - first + 1, reads) << "a slow reader must see gaps in a live source";
}

}  // namespace
}  // namespace rtmot::platform
