// Video outputs through GStreamer, each read back by a GStreamer pipeline started here: MP4 and
// Matroska files (every frame, H.264, index first), RTP on a loopback port, and an RTSP server
// pulled by an rtspsrc client. One decoded frame is saved as a PNG and its overlay checked.
#include <gst/app/gstappsink.h>
#include <gst/gst.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <iostream>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <thread>

#include "child_process.hpp"
#include "common/input_error.hpp"
#include "gst_read_back.hpp"
#include "outputs/encoder_padding.hpp"
#include "outputs/gst_video_output.hpp"
#include "outputs/overlay.hpp"
#include "outputs/rtsp_video_server.hpp"
#include "outputs/video_encoding.hpp"
#include "outputs/video_stream.hpp"
#include "outputs/video_target.hpp"
#include "platform/gst_ptr.hpp"
#include "platform/video_source.hpp"
#include "scratch_folder.hpp"
#include "shared_data.hpp"

namespace rtmot::outputs {
namespace {

using test::read_back;
using test::ReadBack;
using test::to_bgr_sink;

using namespace std::chrono_literals;

constexpr int frame_count = 60;
constexpr const char* test_source = "test://ball?width=320&height=240&num-buffers=60";

VideoTarget target_of(const std::string& text) {
  std::string problem;
  const auto target = parse_video_target(text, problem);
  EXPECT_TRUE(target.has_value()) << text << ": " << problem;
  return target.value_or(VideoTarget{});
}

// One track whose box follows the test pattern's frame number, so a decoded frame can be checked.
messages::FrameResult result_for(std::int64_t frame) {
  messages::FrameResult result;
  result.frame_number = frame;
  tracker::TrackReport track;
  track.id = 7;
  track.class_id = 1;
  track.score = 0.9F;
  track.box = {100.F, 60.F, 120.F, 140.F};
  result.tracks.push_back(track);
  return result;
}

// How a test pushes frames into a live stream, which drops a frame pushed while its encoder is
// busy.
enum class Pacing {
  camera,   // only the pace: what reaches a receiver depends on the encoder's speed
  encoder,  // the pace, then wait until the encoder took the frame: a slow machine (x265 under
            // qemu encodes a few frames a second) makes the test longer, not its result different
};

// Reads the test source and pushes every frame, annotated, into `stream`. `pace`: sleep between
// frames.
int push_test_frames(VideoStream& stream, std::chrono::milliseconds pace,
                     Pacing pacing = Pacing::camera) {
  auto source = platform::open_video_source(test_source);
  Overlay overlay(OverlayFlags{~0U}, [](int) -> std::string_view { return "person"; });
  cv::Mat frame;
  platform::FrameInfo info;
  int pushed = 0;
  while (source->read(frame, info) == platform::ReadStatus::frame) {
    overlay.draw(frame, result_for(info.frame_number), false, OverlayStats{30.0, 12.0});
    stream.push(frame);
    ++pushed;
    std::this_thread::sleep_for(pace);
    const auto deadline = std::chrono::steady_clock::now() + 20s;
    while (pacing == Pacing::encoder &&
           stream.frames_streamed() < static_cast<std::uint64_t>(pushed) &&
           std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(2ms);
    }
  }
  return pushed;
}

// The overlay survived the encoding: the box's left edge has the class's colour, the pixels just
// inside and outside it do not (the test pattern's background is black, its ball white).
void expect_overlay(const cv::Mat& frame, const std::filesystem::path& png) {
  ASSERT_FALSE(frame.empty());
  ASSERT_TRUE(cv::imwrite(png.string(), frame));
  const cv::Mat reread = cv::imread(png.string());
  ASSERT_EQ(reread.size(), cv::Size(320, 240));
  const cv::Scalar colour = class_colour(1);              // the box has its class's colour
  const cv::Vec3b edge = reread.at<cv::Vec3b>(150, 100);  // left edge, mid-height, 2 px thick
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(edge[c], colour[c], 40.0) << "channel " << c;
  const cv::Vec3b outside = reread.at<cv::Vec3b>(150, 90);
  EXPECT_GT(cv::norm(cv::Vec3d(outside) - cv::Vec3d(colour[0], colour[1], colour[2])), 100.0);
}

// Three people side by side, close enough that their labels ("#12 person 0.83") would cover each
// other above their boxes: every label gets its own place, none overlaps another, all inside the
// image; a label with room stays just above its box.
TEST(Overlay, LabelsOfClosePeopleDoNotHideEachOther) {
  const cv::Size image(768, 576);
  const cv::Size label(130, 20);
  std::vector<cv::Rect> placed;
  for (const int x : {300, 330, 360}) {
    placed.push_back(place_label(label, cv::Rect(x, 200, 40, 110), image, placed));
  }
  EXPECT_EQ(placed[0], cv::Rect(300, 180, 130, 20));
  for (std::size_t i = 0; i < placed.size(); ++i) {
    EXPECT_EQ(placed[i] & cv::Rect(cv::Point(0, 0), image), placed[i]) << i;
    for (std::size_t j = 0; j < i; ++j) EXPECT_EQ((placed[i] & placed[j]).area(), 0) << i << j;
  }
  // A box at the top edge: its label goes inside the image, not above it.
  std::vector<cv::Rect> none;
  EXPECT_GE(place_label(label, cv::Rect(10, 0, 40, 80), image, none).y, 0);
}

// Text and lines grow with the frame: a 1080p frame's labels are as readable as a 576p one's.
TEST(Overlay, StyleScalesWithFrameHeight) {
  const OverlayStyle small = OverlayStyle::for_height(240);
  const OverlayStyle demo = OverlayStyle::for_height(576);
  const OverlayStyle full_hd = OverlayStyle::for_height(1080);
  EXPECT_DOUBLE_EQ(demo.font_scale, 0.5);
  EXPECT_LT(small.font_scale, demo.font_scale);
  EXPECT_GT(full_hd.font_scale, demo.font_scale);
  EXPECT_GT(full_hd.text_height, demo.text_height);
  EXPECT_GT(full_hd.line_thickness, demo.line_thickness);
  EXPECT_NE(class_colour(1), class_colour(3));  // person and car differ
}

struct RtpPlayed {
  ReadBack back;
  std::uint64_t streamed{0};  // frames the encoder took
};

// Streams the test frames over RTP to `target` as `codec`, at most at a camera's pace and waiting
// for the encoder, and plays them with GStreamer's sdpdemux (what a player does with a .sdp file)
// from the SDP alone, saved as `sdp_file`.
RtpPlayed play_from_its_sdp(const VideoTarget& target, VideoCodec codec,
                            const std::filesystem::path& sdp_file) {
  { std::ofstream(sdp_file) << rtp_sdp(target, codec); }
  VideoEncoding encoding;
  encoding.codec = codec;
  auto stream = open_video_stream(target, 30.0, encoding);
  const std::string depay =
      codec == VideoCodec::h265 ? "rtph265depay ! avdec_h265" : "rtph264depay ! avdec_h264";
  std::thread pusher;
  RtpPlayed played;
  played.back = read_back(
      "filesrc location=" + sdp_file.string() + " ! sdpdemux latency=0 ! " + depay + to_bgr_sink,
      frame_count / 2, frame_count, 30s, [&] {
        pusher = std::thread([&] {
          std::this_thread::sleep_for(500ms);
          push_test_frames(*stream, 33ms, Pacing::encoder);
        });
      });
  pusher.join();
  stream->close();
  played.streamed = stream->frames_streamed();
  return played;
}

class VideoOutputs : public ::testing::Test {
 protected:
  test::ScratchFolder scratch_{"video"};  // removed when the test passed
  std::filesystem::path folder_ = scratch_.path();
};

TEST(VideoTarget, ReadsEveryKind) {
  EXPECT_EQ(target_of("out/demo.mp4").kind, VideoTargetKind::mp4_file);
  EXPECT_EQ(target_of("file://out/demo.mkv").path, "out/demo.mkv");
  const VideoTarget rtsp = target_of("rtsp://:8554/cam");
  EXPECT_EQ(rtsp.kind, VideoTargetKind::rtsp);
  EXPECT_EQ(rtsp.host, "0.0.0.0");
  EXPECT_EQ(rtsp.port, 8554);
  EXPECT_EQ(rtsp.mount, "/cam");
  const VideoTarget rtp = target_of("rtp://[::1]:5004");
  EXPECT_EQ(rtp.host, "::1");
  EXPECT_EQ(rtp.port, 5004);
  EXPECT_EQ(target_of("display://0").kind, VideoTargetKind::display);
  std::string problem;
  EXPECT_FALSE(parse_video_target("out/demo.avi", problem));
  EXPECT_EQ(problem, "a video file must end in .mp4 or .mkv (H.264), got 'out/demo.avi'");
  EXPECT_FALSE(parse_video_target("rtp://host", problem));
  EXPECT_EQ(problem, "missing ':PORT'");
  EXPECT_FALSE(parse_video_target("http://x/y.mp4", problem));
}

TEST_F(VideoOutputs, MissingFoldersAreCreatedUnwritableTargetsSaySo) {
  EXPECT_EQ(prepare_video_file(target_of((folder_ / "a/b/demo.mp4").string())), "");
  EXPECT_TRUE(std::filesystem::is_directory(folder_ / "a/b"));
  // The video appears only when finished: nothing under its name (nor a temporary) yet.
  EXPECT_TRUE(std::filesystem::is_empty(folder_ / "a/b"));
  std::filesystem::create_directories(folder_ / "dir.mp4");
  EXPECT_EQ(prepare_video_file(target_of((folder_ / "dir.mp4").string())), "is a directory");
  EXPECT_NE(prepare_video_file(target_of("/proc/rtmot/demo.mp4")), "");
}

// display:// on a machine without that display (a board, CI): refused before the run with what is
// missing: the package of ximagesink (gstreamer1.0-x, which the setup did not install and the
// error blamed on x264enc), or the X server, with the outputs that work instead.
TEST_F(VideoOutputs, DisplayWithoutXServerOrPluginSaysWhich) {
  const std::string problem = check_video_elements(target_of("display://97"));
  const platform::gst::ObjectPtr<GstElementFactory> sink{gst_element_factory_find("ximagesink")};
  if (sink) {
    EXPECT_NE(problem.find("no display :97"), std::string::npos) << problem;
    EXPECT_NE(problem.find("/tmp/.X11-unix/X97"), std::string::npos) << problem;
    EXPECT_NE(problem.find("rtsp://"), std::string::npos) << problem;
  } else {
    EXPECT_NE(problem.find("ximagesink (in gstreamer1.0-x)"), std::string::npos) << problem;
  }
  EXPECT_EQ(problem.find("x264enc"), std::string::npos) << problem;
}

TEST_F(VideoOutputs, Mp4HasEveryFrameAsH264IndexFirst) {
  const auto path = folder_ / "demo.mp4";
  const VideoTarget target = target_of(path.string());
  ASSERT_EQ(check_video_elements(target), "");
  auto stream = open_video_stream(target, 30.0);
  EXPECT_EQ(push_test_frames(*stream, 0ms), frame_count);
  stream->close();
  EXPECT_EQ(stream->frames_streamed(), static_cast<std::uint64_t>(frame_count));  // a file waits

  const ReadBack back = read_back(
      "filesrc location=" + path.string() + " ! qtdemux ! video/x-h264 ! avdec_h264" + to_bgr_sink,
      frame_count / 2, 10000, 60s);
  EXPECT_EQ(back.frames, frame_count);
  expect_overlay(back.saved, folder_ / "frame30.png");
  // Browsers: H.264 in `avc1` sample entries, and the index (moov) before the data (mdat).
  std::ifstream file(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  EXPECT_NE(bytes.find("avc1"), std::string::npos);
  ASSERT_NE(bytes.find("moov"), std::string::npos);
  EXPECT_LT(bytes.find("moov"), bytes.find("mdat"));
}

// A writer killed by SIGKILL leaves its PATH.tmp-PID (it cannot remove it): the next video
// written to PATH removes it (common/stale_temporaries.hpp).
TEST_F(VideoOutputs, AKilledWritersTemporaryGoesWithTheNextVideo) {
  const auto path = folder_ / "demo.mkv";
  const pid_t gone = ::fork();
  if (gone == 0) ::_exit(0);
  ASSERT_GT(gone, 0);
  ::waitpid(gone, nullptr, 0);
  const auto left = folder_ / ("demo.mkv.tmp-" + std::to_string(gone));
  { std::ofstream(left) << "half a video"; }
  auto stream = open_video_stream(target_of(path.string()), 30.0);
  EXPECT_EQ(push_test_frames(*stream, 0ms), frame_count);
  stream->close();
  EXPECT_FALSE(std::filesystem::exists(left));
  EXPECT_GT(std::filesystem::file_size(path), 0U);
}

TEST_F(VideoOutputs, MkvHasEveryFrame) {
  const auto path = folder_ / "demo.mkv";
  auto stream = open_video_stream(target_of(path.string()), 30.0);
  EXPECT_EQ(push_test_frames(*stream, 0ms), frame_count);
  stream->close();
  const ReadBack back = read_back("filesrc location=" + path.string() +
                                      " ! matroskademux ! video/x-h264 ! avdec_h264" + to_bgr_sink,
                                  5, 10000, 60s);
  EXPECT_EQ(back.frames, frame_count);
  expect_overlay(back.saved, folder_ / "frame5.png");
}

TEST_F(VideoOutputs, RtpStreamReachesAReceiver) {
  const unsigned short port = test::free_tcp_port();  // free for UDP too in practice
  auto stream = open_video_stream(target_of("rtp://127.0.0.1:" + std::to_string(port)), 30.0);
  std::thread pusher;
  // A large receive buffer: on a loaded machine the decoder thread may fall behind for a moment,
  // and a datagram the kernel drops for want of room is a lost frame. The sender starts once the
  // receiver's socket is bound (the pipeline is playing): a stream's
  // first keyframe sent into nothing would leave the decoder waiting for the next one.
  const ReadBack back =
      read_back("udpsrc address=127.0.0.1 buffer-size=8388608 port=" + std::to_string(port) +
                    " caps=\"application/x-rtp,media=video,encoding-name=H264,payload=96,"
                    "clock-rate=90000\" ! rtph264depay ! avdec_h264" +
                    to_bgr_sink,
                frame_count / 2, frame_count, 30s, [&] {
                  pusher = std::thread([&] {
                    std::this_thread::sleep_for(200ms);
                    // At most a 30 fps camera's pace.
                    push_test_frames(*stream, 33ms, Pacing::encoder);
                  });
                });
  pusher.join();
  stream->close();
  EXPECT_EQ(stream->frames_streamed(), static_cast<std::uint64_t>(frame_count));
  EXPECT_EQ(back.frames, frame_count);
  expect_overlay(back.saved, folder_ / "rtp.png");
}

// The SDP the log prints is all a player needs: GStreamer's sdpdemux (what a player does with a
// .sdp file) receives and decodes the stream from it alone.
TEST_F(VideoOutputs, RtpSdpIsEnoughForAPlayer) {
  const unsigned short port = test::free_tcp_port();
  const VideoTarget target = target_of("rtp://127.0.0.1:" + std::to_string(port));
  const std::string sdp = rtp_sdp(target);
  EXPECT_NE(sdp.find("m=video " + std::to_string(port) + " RTP/AVP 96\n"), std::string::npos);
  EXPECT_NE(sdp.find("c=IN IP4 127.0.0.1\n"), std::string::npos);
  EXPECT_NE(rtp_sdp(target_of("rtp://[::1]:5004")).find("c=IN IP6 ::1\n"), std::string::npos);
  const RtpPlayed played = play_from_its_sdp(target, VideoCodec::h264, folder_ / "stream.sdp");
  EXPECT_EQ(played.streamed, static_cast<std::uint64_t>(frame_count));
  EXPECT_GE(played.back.frames, frame_count / 2);
  EXPECT_LE(played.back.frames, frame_count);
  expect_overlay(played.back.saved, folder_ / "sdp.png");
}

TEST_F(VideoOutputs, RtspServerIsPulledByAClient) {
  const unsigned short port = test::free_tcp_port();
  const VideoTarget target = target_of("rtsp://127.0.0.1:" + std::to_string(port) + "/tracks");
  RtspVideoServer server(target, 30.0);
  ReadBack back;
  std::thread pusher;
  back = read_back("rtspsrc location=rtsp://127.0.0.1:" + std::to_string(port) +
                       "/tracks protocols=tcp latency=0 ! rtph264depay ! avdec_h264" + to_bgr_sink,
                   frame_count / 2, frame_count, 30s, [&] {
                     pusher = std::thread([&] {
                       // Frames go out once a client has the media (a live stream starts when
                       // watched).
                       const auto deadline = std::chrono::steady_clock::now() + 20s;
                       while (!server.has_client() && std::chrono::steady_clock::now() < deadline) {
                         std::this_thread::sleep_for(10ms);
                       }
                       std::this_thread::sleep_for(300ms);  // the client's PLAY reached the media
                       push_test_frames(server, 15ms);
                     });
                   });
  pusher.join();
  const std::uint64_t streamed = server.frames_streamed();
  server.close();
  // A live stream may drop the oldest of its two queued frames when the encoder falls behind
  // (seen under AddressSanitizer: 57 of 60): every frame that entered the stream reached the
  // client.
  EXPECT_GE(streamed, static_cast<std::uint64_t>(frame_count / 2));
  EXPECT_EQ(static_cast<std::uint64_t>(back.frames), streamed);
  expect_overlay(back.saved, folder_ / "rtsp.png");
}

// A server closed while a client watches hangs up on it (the client hears the end instead of
// waiting for frames until its own timeout), and nothing of the server is used after it is gone:
// clients are served on gst-rtsp-server's threads, which outlive the server's main loop, and a
// client's teardown unprepares the media there, later. CI once aborted on that (a late callback
// locked the mutex of a destroyed server); under AddressSanitizer the same is a use after free.
TEST_F(VideoOutputs, ClosedRtspServerHangsUpOnItsClientsAndLeavesNoCallbackBehind) {
  const unsigned short port = test::free_tcp_port();
  const VideoTarget target = target_of("rtsp://127.0.0.1:" + std::to_string(port) + "/tracks");
  auto server = std::make_unique<RtspVideoServer>(target, 30.0);
  GError* raw_error = nullptr;
  const platform::gst::ObjectPtr<GstElement> client(gst_parse_launch(
      ("rtspsrc location=rtsp://127.0.0.1:" + std::to_string(port) +
       "/tracks protocols=tcp latency=0 ! rtph264depay ! avdec_h264 ! fakesink sync=false")
          .c_str(),
      &raw_error));
  const platform::gst::ErrorPtr error(raw_error);
  ASSERT_TRUE(client && !error) << (error ? error->message : "");
  const platform::gst::ObjectPtr<GstBus> bus(gst_element_get_bus(client.get()));
  gst_element_set_state(client.get(), GST_STATE_PLAYING);
  const auto deadline = std::chrono::steady_clock::now() + 20s;
  while (!server->has_client() && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(10ms);
  }
  ASSERT_TRUE(server->has_client());
  std::this_thread::sleep_for(300ms);  // the client's PLAY reached the media
  push_test_frames(*server, 15ms);
  EXPECT_GT(server->frames_streamed(), 0U);

  const auto closed_at = std::chrono::steady_clock::now();
  server->close();
  server.reset();
  const platform::gst::MessagePtr end(
      gst_bus_timed_pop_filtered(bus.get(), 10 * GST_SECOND,
                                 static_cast<GstMessageType>(GST_MESSAGE_ERROR | GST_MESSAGE_EOS)));
  EXPECT_NE(end, nullptr) << "the client was not told that the stream ended";
  std::cout << "client heard the end after "
            << std::chrono::duration<double>(std::chrono::steady_clock::now() - closed_at).count()
            << " s\n";
  // The client's teardown and the media's unprepare run now, with the server gone.
  gst_element_set_state(client.get(), GST_STATE_NULL);
  std::this_thread::sleep_for(500ms);
}

// x264 refuses odd sides and sides under 16: the RTSP server's pipeline, built before the size is
// known, pads at the first frame as the file and RTP outputs do (outputs/encoder_padding.hpp).
// Before, a 33x17 source reached no client: x264enc refused the caps and the media failed.
TEST_F(VideoOutputs, RtspServerPadsAnOddTinyFrame) {
  const unsigned short port = test::free_tcp_port();
  const VideoTarget target = target_of("rtsp://127.0.0.1:" + std::to_string(port) + "/tiny");
  RtspVideoServer server(target, 30.0);
  auto source = platform::open_video_source("test://ball?width=33&height=17&num-buffers=60");
  std::vector<cv::Mat> frames;
  cv::Mat frame;
  platform::FrameInfo info;
  while (source->read(frame, info) == platform::ReadStatus::frame) {
    frame.setTo(cv::Scalar(0, 200, 0));  // uniform green: what survives the encoding is checked
    frames.push_back(frame.clone());
  }
  ASSERT_EQ(frames.size(), 60U);
  ASSERT_EQ(frames[0].size(), cv::Size(33, 17));
  std::thread pusher;
  const ReadBack back =
      read_back("rtspsrc location=rtsp://127.0.0.1:" + std::to_string(port) +
                    "/tiny protocols=tcp latency=0 ! rtph264depay ! avdec_h264" + to_bgr_sink,
                5, 30, 30s, [&] {
                  pusher = std::thread([&] {
                    const auto deadline = std::chrono::steady_clock::now() + 20s;
                    while (!server.has_client() && std::chrono::steady_clock::now() < deadline) {
                      std::this_thread::sleep_for(10ms);
                    }
                    std::this_thread::sleep_for(300ms);
                    for (const auto& f : frames) {
                      server.push(f);
                      std::this_thread::sleep_for(15ms);
                    }
                  });
                });
  pusher.join();
  server.close();
  // Frames decoded without their keyframe (a client that joined late) are left out.
  EXPECT_GT(back.frames, 10);
  ASSERT_FALSE(back.saved.empty());
  EXPECT_EQ(back.saved.size(), cv::Size(34, 18));  // even sides, black on the right and bottom
  // A frame this small is coded coarsely at first: the picture is green, the corner darker.
  const cv::Vec3b inside = back.saved.at<cv::Vec3b>(8, 16);
  EXPECT_GT(inside[1], 100);
  EXPECT_GT(inside[1], inside[0] + 60);
  EXPECT_GT(inside[1], inside[2] + 60);
  const cv::Vec3b corner = back.saved.at<cv::Vec3b>(17, 33);
  EXPECT_LT(corner[1] + 30, inside[1]);
}

// The other encoders of this machine, chosen by name, read back frame by frame: OpenH264 (the
// H.264 encoder where plugins-ugly is absent) in MP4, x265 in MP4 (hvc1) and Matroska, and H.265
// over RTP from its SDP alone.
TEST_F(VideoOutputs, OpenH264Mp4HasEveryFrame) {
  if (!gstreamer_has("openh264enc")) GTEST_SKIP() << "no openh264enc (gstreamer1.0-plugins-bad)";
  const auto path = folder_ / "openh264.mp4";
  VideoEncoding encoding;
  encoding.encoder = "openh264enc";
  const VideoTarget target = target_of(path.string());
  ASSERT_EQ(check_video_elements(target, encoding), "");
  auto stream = open_video_stream(target, 30.0, encoding);
  EXPECT_EQ(push_test_frames(*stream, 0ms), frame_count);
  stream->close();
  const ReadBack back = read_back(
      "filesrc location=" + path.string() + " ! qtdemux ! video/x-h264 ! avdec_h264" + to_bgr_sink,
      frame_count / 2, 10000, 60s);
  EXPECT_EQ(back.frames, frame_count);
  expect_overlay(back.saved, folder_ / "openh264.png");
  std::ifstream file(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  EXPECT_NE(bytes.find("avc1"), std::string::npos);
}

TEST_F(VideoOutputs, H265FilesHaveEveryFrame) {
  VideoEncoding encoding;
  encoding.codec = VideoCodec::h265;
  for (const std::string name : {"h265.mp4", "h265.mkv"}) {
    const auto path = folder_ / name;
    const VideoTarget target = target_of(path.string());
    ASSERT_EQ(check_video_elements(target, encoding), "");
    auto stream = open_video_stream(target, 30.0, encoding);
    EXPECT_EQ(push_test_frames(*stream, 0ms), frame_count);
    stream->close();
    const std::string demux = name == "h265.mp4" ? "qtdemux" : "matroskademux";
    const ReadBack back = read_back("filesrc location=" + path.string() + " ! " + demux +
                                        " ! video/x-h265 ! avdec_h265" + to_bgr_sink,
                                    frame_count / 2, 10000, 60s);
    EXPECT_EQ(back.frames, frame_count) << name;
    expect_overlay(back.saved, folder_ / (name + ".png"));
    if (name == "h265.mp4") {
      std::ifstream file(path, std::ios::binary);
      const std::string bytes((std::istreambuf_iterator<char>(file)),
                              std::istreambuf_iterator<char>());
      EXPECT_NE(bytes.find("hvc1"), std::string::npos);
    }
  }
}

// x265 wants a picture of at least one coding tree unit: below it, x265 3.5 shrank its CTU and
// wrote past its buffers (34x18: SIGABRT "free(): invalid next size"). Small frames are padded to
// 64 a side for H.265 (16 for H.264): every frame is in the file, at the padded size, the
// picture at its top left and black on the right and bottom.
TEST_F(VideoOutputs, SmallFramesArePaddedToWhatTheCodecTakes) {
  EXPECT_EQ(min_encoder_side(VideoCodec::h264), 16);
  EXPECT_EQ(min_encoder_side(VideoCodec::h265), 64);
  const struct {
    VideoCodec codec;
    cv::Size frame;
    cv::Size padded;
  } sizes[] = {{VideoCodec::h265, {34, 18}, {64, 64}},
               {VideoCodec::h265, {40, 18}, {64, 64}},
               {VideoCodec::h265, {33, 17}, {64, 64}},
               {VideoCodec::h265, {62, 100}, {64, 100}},
               {VideoCodec::h264, {33, 17}, {34, 18}}};
  for (const auto& size : sizes) {
    VideoEncoding encoding;
    encoding.codec = size.codec;
    const auto path =
        folder_ / (std::to_string(size.frame.width) + "x" + std::to_string(size.frame.height) +
                   "-" + std::string(codec_title(size.codec)) + ".mkv");
    auto stream = open_video_stream(target_of(path.string()), 30.0, encoding);
    const cv::Mat grey(size.frame, CV_8UC3, cv::Scalar(128, 128, 128));
    for (int i = 0; i < 10; ++i) stream->push(grey);
    stream->close();
    const std::string parse = size.codec == VideoCodec::h265 ? "h265" : "h264";
    const ReadBack back =
        read_back("filesrc location=" + path.string() + " ! matroskademux ! video/x-" + parse +
                      " ! avdec_" + parse + to_bgr_sink,
                  9, 10000, 60s);
    EXPECT_EQ(back.frames, 10) << path;
    ASSERT_EQ(back.saved.size(), size.padded) << path;
    const cv::Vec3b inside = back.saved.at<cv::Vec3b>(size.frame.height / 2, size.frame.width / 2);
    const cv::Vec3b corner =
        back.saved.at<cv::Vec3b>(size.padded.height - 1, size.padded.width - 1);
    EXPECT_NEAR(inside[1], 128, 20) << path;
    if (size.padded != size.frame) {
      EXPECT_LT(corner[1], 40) << path;
    }
  }
}

TEST_F(VideoOutputs, H265RtpPlaysFromItsSdp) {
  const unsigned short port = test::free_tcp_port();
  const VideoTarget target = target_of("rtp://127.0.0.1:" + std::to_string(port));
  const std::string sdp = rtp_sdp(target, VideoCodec::h265);
  EXPECT_NE(sdp.find("a=rtpmap:96 H265/90000\n"), std::string::npos);
  // CI's aarch64 stage (qemu) encoded 20 of 60 frames at a camera's pace: the test waits for the
  // encoder, and every frame is encoded and sent.
  const RtpPlayed played = play_from_its_sdp(target, VideoCodec::h265, folder_ / "h265.sdp");
  EXPECT_EQ(played.streamed, static_cast<std::uint64_t>(frame_count));
  EXPECT_GE(played.back.frames, frame_count / 2);
  EXPECT_LE(played.back.frames, frame_count);
  expect_overlay(played.back.saved, folder_ / "h265-rtp.png");
}

// --bitrate is what the file gets: the first 8 s of the demo video (80 frames at 10 fps) at 300
// and 1200 kbit/s, through x264 and OpenH264: each file is within a third of bitrate x duration
// (x264 lands at about 0.75 of it, OpenH264 within a few percent), so the second is about 4
// times the first.
TEST_F(VideoOutputs, BitrateSetsTheFilesSize) {
  constexpr int frames = 80;
  constexpr double fps = 10.0;
  const auto vtest = test::shared_path("data/video/vtest.avi");
  RTMOT_REQUIRE_FILE(vtest);
  std::vector<cv::Mat> pictures;
  {
    auto source = platform::open_video_source(vtest.string());
    cv::Mat frame;
    platform::FrameInfo info;
    while (static_cast<int>(pictures.size()) < frames &&
           source->read(frame, info) == platform::ReadStatus::frame) {
      pictures.push_back(frame.clone());
    }
  }
  ASSERT_EQ(static_cast<int>(pictures.size()), frames);
  for (const std::string encoder : {"x264enc", "openh264enc"}) {
    if (!gstreamer_has(encoder)) continue;
    for (const int kbps : {300, 1200}) {
      const auto path = folder_ / (encoder + "-" + std::to_string(kbps) + ".mkv");
      VideoEncoding encoding;
      encoding.encoder = encoder;
      encoding.bitrate_kbps = kbps;
      auto stream = open_video_stream(target_of(path.string()), fps, encoding);
      for (const auto& picture : pictures) stream->push(picture);
      stream->close();
      const double expected_bytes = kbps * 1000.0 / 8.0 * frames / fps;
      const double size = static_cast<double>(std::filesystem::file_size(path));
      EXPECT_GT(size, expected_bytes * 2.0 / 3.0) << encoder << " at " << kbps << " kbit/s";
      EXPECT_LT(size, expected_bytes * 4.0 / 3.0) << encoder << " at " << kbps << " kbit/s";
    }
  }
}

// A hardware encoder that is there but does not start (a Jetson container without the encoder's
// device): `auto` falls back to software and the video is whole; asked for by name or as
// `hardware`, it is exit 8 and no file. Stood in for by an element this GStreamer lacks, which
// fails where a device that cannot open fails: as the pipeline starts.
TEST_F(VideoOutputs, HardwareEncoderThatDoesNotStartFallsBackUnderAuto) {
  const VideoEncoder broken{"rtmotabsenth264enc", VideoCodec::h264, true, "nowhere"};
  const auto path = folder_ / "fallback.mp4";
  GstVideoOutput automatic(target_of(path.string()), 30.0, VideoEncoding{}, &broken);
  EXPECT_EQ(push_test_frames(automatic, 0ms), frame_count);
  automatic.close();
  const ReadBack back = read_back(
      "filesrc location=" + path.string() + " ! qtdemux ! video/x-h264 ! avdec_h264" + to_bgr_sink,
      frame_count / 2, 10000, 60s);
  EXPECT_EQ(back.frames, frame_count);
  expect_overlay(back.saved, folder_ / "fallback.png");

  VideoEncoding hardware;
  hardware.encoder = "hardware";
  const auto refused = folder_ / "refused.mp4";
  GstVideoOutput asked(target_of(refused.string()), 30.0, hardware, &broken);
  try {
    push_test_frames(asked, 0ms);
    FAIL() << "a hardware encoder that cannot start wrote a video";
  } catch (const InputError& error) {
    EXPECT_EQ(error.exit_code(), ExitCode::encoder_failed);
    EXPECT_NE(std::string(error.what()).find("rtmotabsenth264enc"), std::string::npos)
        << error.what();
  }
  EXPECT_FALSE(std::filesystem::exists(refused));
  for (const auto& entry : std::filesystem::directory_iterator(folder_)) {
    EXPECT_EQ(entry.path().string().find(".tmp-"), std::string::npos) << entry.path();
  }
}

// A full disk mid-run is an error (exit code io_error), not a video silently lost.
TEST_F(VideoOutputs, FullDiskIsAnError) {
  if (!std::filesystem::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  std::filesystem::create_symlink("/dev/full", folder_ / "full.mkv");
  auto stream = open_video_stream(target_of((folder_ / "full.mkv").string()), 30.0);
  try {
    push_test_frames(*stream, 0ms);
    stream->close();
    FAIL() << "writing to a full disk succeeded";
  } catch (const InputError& error) {
    EXPECT_EQ(error.exit_code(), ExitCode::io_error);
    EXPECT_NE(std::string(error.what()).find("No space left"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace rtmot::outputs
