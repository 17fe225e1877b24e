// Which encoder the annotated video gets (outputs/video_encoding.hpp), on the registries of the
// boards we target, stood in for by the elements each one's GStreamer has: a Jetson
// (nvv4l2h264enc with its nvvidconv), a board with a V4L2 encoder (v4l2h264enc), a PC (x264enc), a
// PC without plugins-ugly (openh264enc only). The real encoders of this machine are run and read
// back in video_output_test.cpp.
#include "outputs/video_encoding.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace rtmot::outputs {
namespace {

HasElement registry(std::set<std::string> elements) {
  return [elements = std::move(elements)](std::string_view name) {
    return elements.count(std::string(name)) > 0;
  };
}

const std::set<std::string> kPc = {"x264enc", "openh264enc", "x265enc", "h264parse", "h265parse"};

std::set<std::string> pc_with(std::set<std::string> more) {
  more.insert(kPc.begin(), kPc.end());
  return more;
}

std::string chosen(const VideoEncoding& encoding, const HasElement& has) {
  const EncoderChoice choice = choose_encoder(encoding, has);
  return choice.encoder != nullptr ? std::string(choice.encoder->element)
                                   : "none: " + choice.problem;
}

TEST(VideoEncoder, AutoTakesTheBoardsHardwareEncoderThenSoftware) {
  const VideoEncoding h264;
  EXPECT_EQ(chosen(h264, registry(pc_with({"nvv4l2h264enc", "nvvidconv"}))), "nvv4l2h264enc");
  EXPECT_EQ(chosen(h264, registry(pc_with({"v4l2h264enc"}))), "v4l2h264enc");
  EXPECT_EQ(chosen(h264, registry(kPc)), "x264enc");
  // Jetson's encoder without its converter (frames never reach NVMM memory) is not usable.
  EXPECT_EQ(chosen(h264, registry(pc_with({"nvv4l2h264enc"}))), "x264enc");
  // No plugins-ugly: OpenH264 from plugins-bad.
  EXPECT_EQ(chosen(h264, registry({"openh264enc", "h264parse"})), "openh264enc");
  VideoEncoding h265;
  h265.codec = VideoCodec::h265;
  EXPECT_EQ(chosen(h265, registry(pc_with({"nvv4l2h265enc", "nvvidconv"}))), "nvv4l2h265enc");
  EXPECT_EQ(chosen(h265, registry(kPc)), "x265enc");
}

// The log line says why: what was looked for first and was absent.
TEST(VideoEncoder, TheChoiceSaysWhy) {
  const EncoderChoice fallback = choose_encoder(VideoEncoding{}, registry(kPc));
  EXPECT_EQ(fallback.why, "auto: nvv4l2h264enc, v4l2h264enc absent");
  EXPECT_FALSE(fallback.encoder->hardware);
  const EncoderChoice jetson =
      choose_encoder(VideoEncoding{}, registry(pc_with({"nvv4l2h264enc", "nvvidconv"})));
  EXPECT_TRUE(jetson.encoder->hardware);
  EXPECT_EQ(jetson.why, "auto: the first of nvv4l2h264enc, v4l2h264enc, x264enc, openh264enc");
}

TEST(VideoEncoder, HardwareOrSoftwareOnlyWhenAskedAndAbsentSaysWhereFrom) {
  VideoEncoding software;
  software.encoder = "software";
  EXPECT_EQ(chosen(software, registry(pc_with({"nvv4l2h264enc", "nvvidconv"}))), "x264enc");
  VideoEncoding hardware;
  hardware.encoder = "hardware";
  EXPECT_EQ(chosen(hardware, registry(pc_with({"v4l2h264enc"}))), "v4l2h264enc");
  const std::string none = chosen(hardware, registry(kPc));
  EXPECT_NE(none.find("no hardware H.264 encoder in this GStreamer"), std::string::npos) << none;
  EXPECT_NE(none.find("nvv4l2h264enc (from NVIDIA's L4T GStreamer plugins"), std::string::npos)
      << none;
  EXPECT_NE(none.find("v4l2h264enc (from gstreamer1.0-plugins-good"), std::string::npos) << none;
  EXPECT_EQ(none.find("x264enc"), std::string::npos) << none;
}

TEST(VideoEncoder, AnElementByNameMustEncodeTheCodecAndExist) {
  VideoEncoding named;
  named.encoder = "openh264enc";
  EXPECT_EQ(chosen(named, registry(kPc)), "openh264enc");
  named.codec = VideoCodec::h265;
  EXPECT_EQ(chosen(named, registry(kPc)),
            "none: openh264enc encodes H.264, not H.265 (output.video_codec, --video-codec)");
  named.codec = VideoCodec::h264;
  named.encoder = "nvv4l2h264enc";
  EXPECT_EQ(chosen(named, registry(kPc)),
            "none: this GStreamer lacks nvv4l2h264enc (from NVIDIA's L4T GStreamer plugins "
            "(JetPack)), nvvidconv");
}

TEST(VideoEncoder, RequestsAreCheckedWithTheNearestName) {
  std::string problem;
  EXPECT_EQ(parse_encoder_request("v4l2h264enc", problem), "v4l2h264enc");
  EXPECT_EQ(parse_encoder_request("hardware", problem), "hardware");
  EXPECT_FALSE(parse_encoder_request("openh264enk", problem));
  EXPECT_NE(problem.find("(did you mean openh264enc?)"), std::string::npos) << problem;
  EXPECT_NE(problem.find("auto, hardware, software or an encoder element"), std::string::npos);
  EXPECT_FALSE(parse_encoder_request("x264", problem));  // GStreamer's docs' short name
  EXPECT_NE(problem.find("(did you mean x264enc?)"), std::string::npos) << problem;
  EXPECT_FALSE(parse_encoder_request("x265", problem));
  EXPECT_NE(problem.find("(did you mean x265enc?)"), std::string::npos) << problem;
}

// Each encoder is given the bitrate in its own unit: x264enc and x265enc take kbit/s, the others
// bit/s (a Jetson at 2048 bit/s would send mush, x264 at 2048000 kbit/s would never limit).
TEST(VideoEncoder, BitrateInEachEncodersUnit) {
  const auto launch = [](std::string_view element, bool live) {
    for (const auto& encoder : video_encoders()) {
      if (encoder.element == element) return encoder_launch(encoder, 2048, 60, live);
    }
    return std::string("unknown");
  };
  EXPECT_NE(launch("x264enc", false).find("bitrate=2048 "), std::string::npos);
  EXPECT_NE(launch("x265enc", true).find("bitrate=2048 "), std::string::npos);
  EXPECT_NE(launch("openh264enc", false).find("bitrate=2048000 "), std::string::npos);
  EXPECT_NE(launch("nvv4l2h264enc", true).find("bitrate=2048000 "), std::string::npos);
  EXPECT_NE(launch("v4l2h264enc", true).find("video_bitrate=2048000,"), std::string::npos);
  // Jetson's encoder takes frames in NVMM memory only.
  EXPECT_EQ(launch("nvv4l2h264enc", true).find("nvvidconv ! video/x-raw(memory:NVMM)"), 0U);
  for (const auto& encoder : video_encoders()) {
    const std::string text = encoder_launch(encoder, 2048, 60, false);
    EXPECT_NE(text.find(encoder.codec == VideoCodec::h264 ? "! h264parse ! " : "! h265parse ! "),
              std::string::npos)
        << text;
  }
}

}  // namespace
}  // namespace rtmot::outputs
