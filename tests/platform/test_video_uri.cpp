#include <gtest/gtest.h>

#include <utility>

#include "common/input_error.hpp"
#include "platform/video_uri.hpp"

namespace rtmot::platform {
namespace {

TEST(VideoUri, FileUriWithAbsolutePath) {
  const VideoUri uri = parse_video_uri("file:///data/video/vtest.avi");
  EXPECT_EQ(uri.kind, SourceKind::file);
  EXPECT_EQ(uri.location, "/data/video/vtest.avi");
  EXPECT_EQ(uri.text, "file:///data/video/vtest.avi");
  EXPECT_FALSE(is_live(uri));
}

TEST(VideoUri, FileUriWithRelativePathAndEscapes) {
  EXPECT_EQ(parse_video_uri("file://videos/a%20b.avi").location, "videos/a b.avi");
  EXPECT_EQ(parse_video_uri("file://localhost/tmp/x.mp4").location, "/tmp/x.mp4");
}

TEST(VideoUri, FileUriQueryReTimesTheRecording) {
  const VideoUri retimed = parse_video_uri("file:///data/vtest.avi?fps=7");
  EXPECT_EQ(retimed.location, "/data/vtest.avi");
  EXPECT_DOUBLE_EQ(retimed.recording.fps, 7.0);
  EXPECT_DOUBLE_EQ(parse_video_uri("file:///data/vtest.avi").recording.fps, 0.0);
  // A '?' of the file's name is written %3F; a plain path keeps one literally.
  EXPECT_EQ(parse_video_uri("file:///data/what%3F.avi").location, "/data/what?.avi");
  EXPECT_DOUBLE_EQ(parse_video_uri("file:///data/what%3F.avi").recording.fps, 0.0);
  EXPECT_EQ(parse_video_uri("/data/what?.avi").location, "/data/what?.avi");
}

TEST(VideoUri, FileUriBadQueryNamesTheParameter) {
  const std::pair<const char*, const char*> bad[] = {
      {"file:///v.avi?fps=0", "fps"},       {"file:///v.avi?fps=fast", "fps"},
      {"file:///v.avi?fps=7&fps=8", "fps"}, {"file:///v.avi?speed=2", "speed"},
      {"file:///v.avi?fps", "fps"},         {"file://?fps=7", "path"}};
  for (const auto& [uri, field] : bad) {
    try {
      parse_video_uri(uri);
      ADD_FAILURE() << uri << ": no error";
    } catch (const InputError& error) {
      EXPECT_EQ(error.field(), field) << uri << ": " << error.what();
      EXPECT_EQ(error.file(), uri);
    }
  }
}

TEST(VideoUri, PlainPathIsAFileTakenLiterally) {
  const VideoUri uri = parse_video_uri("../shared/a%20b:c.avi");
  EXPECT_EQ(uri.kind, SourceKind::file);
  EXPECT_EQ(uri.location, "../shared/a%20b:c.avi");
}

TEST(VideoUri, CamerasAndStreamsAreLive) {
  const VideoUri v4l2 = parse_video_uri("v4l2:///dev/video2");
  EXPECT_EQ(v4l2.kind, SourceKind::v4l2);
  EXPECT_EQ(v4l2.location, "/dev/video2");
  EXPECT_TRUE(is_live(v4l2));
  EXPECT_EQ(parse_video_uri("v4l2://1").location, "/dev/video1");

  const VideoUri csi = parse_video_uri("csi://1");
  EXPECT_EQ(csi.kind, SourceKind::csi);
  EXPECT_EQ(csi.sensor_id, 1);
  EXPECT_TRUE(is_live(csi));

  const VideoUri rtsp = parse_video_uri("rtsp://192.0.2.7:8554/cam?profile=1");
  EXPECT_EQ(rtsp.kind, SourceKind::rtsp);
  EXPECT_EQ(rtsp.location, "rtsp://192.0.2.7:8554/cam?profile=1");
  EXPECT_TRUE(is_live(rtsp));
}

// kSourceSchemes is what the parser reads: every scheme in it is known to the parser (a bare
// "scheme://" may lack its path, never be an unknown scheme), names its kind back, and an unknown
// scheme is refused listing them all.
TEST(VideoUri, SchemesAreTheTablesNames) {
  for (const auto& [kind, scheme] : kSourceSchemes.entries()) {
    SCOPED_TRACE(std::string(scheme));
    try {
      EXPECT_EQ(parse_video_uri(std::string(scheme) + "://").kind, kind);
    } catch (const InputError& error) {
      EXPECT_NE(error.field(), "scheme") << error.what();
    }
    EXPECT_EQ(kSourceSchemes.parse(to_string(kind)), kind);
  }
  EXPECT_STREQ(to_string(SourceKind::rtsp), "rtsp");
  EXPECT_EQ(parse_video_uri("RTSPS://camera/live").kind, SourceKind::rtsp);
  EXPECT_EQ(parse_video_uri("images:///tmp/frames?fps=5").kind, SourceKind::images);
  try {
    parse_video_uri("http://example.com/x.avi");
    ADD_FAILURE() << "accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what())
                  .find("unknown scheme 'http' (known: file, v4l2, csi, rtsp, rtsps, test or "
                        "images)"),
              std::string::npos)
        << error.what();
  }
}

TEST(VideoUri, TestSourceDefaults) {
  const VideoUri uri = parse_video_uri("test://");
  EXPECT_EQ(uri.kind, SourceKind::test);
  EXPECT_EQ(uri.test.pattern, "smpte");
  EXPECT_EQ(uri.test.error_after, -1);
  EXPECT_FALSE(is_live(uri));
}

TEST(VideoUri, TestSourceParameters) {
  const VideoUri uri = parse_video_uri(
      "test://ball?width=64&height=48&fps=12.5&num-buffers=9&is-live=true&error-after=3&"
      "stall-after=2&stall-ms=150&eos-after=7");
  const TestSourceParams& test = uri.test;
  EXPECT_EQ(test.pattern, "ball");
  EXPECT_EQ(test.width, 64);
  EXPECT_EQ(test.height, 48);
  EXPECT_DOUBLE_EQ(test.fps, 12.5);
  EXPECT_EQ(test.num_buffers, 9);
  EXPECT_TRUE(test.is_live);
  EXPECT_EQ(test.error_after, 3);
  EXPECT_EQ(test.stall_after, 2);
  EXPECT_EQ(test.stall_ms, 150);
  EXPECT_EQ(test.eos_after, 7);
  EXPECT_TRUE(is_live(uri));
}

// Each bad URI must fail with source_failed and name the URI and the part that is wrong.
struct BadUri {
  const char* uri;
  const char* part;
};

class BadVideoUri : public testing::TestWithParam<BadUri> {};

TEST_P(BadVideoUri, ThrowsInputErrorNamingThePart) {
  const BadUri bad = GetParam();
  try {
    parse_video_uri(bad.uri);
    FAIL() << "accepted " << bad.uri;
  } catch (const InputError& error) {
    EXPECT_EQ(error.exit_code(), ExitCode::source_failed);
    EXPECT_EQ(error.file(), bad.uri);
    EXPECT_EQ(error.field(), bad.part);
    EXPECT_NE(std::string(error.what()).find(bad.uri), std::string::npos) << error.what();
  }
}

INSTANTIATE_TEST_SUITE_P(
    Examples, BadVideoUri,
    testing::Values(BadUri{"", ""}, BadUri{"http://example.com/x.avi", "scheme"},
                    BadUri{"file://", "path"}, BadUri{"file:///a%2", "path"},
                    BadUri{"v4l2://", "device"}, BadUri{"v4l2://video0", "device"},
                    BadUri{"csi://", "sensor-id"}, BadUri{"csi://left", "sensor-id"},
                    BadUri{"csi://99", "sensor-id"}, BadUri{"rtsp://", "host"},
                    BadUri{"rtsp://:554/x", "host"}, BadUri{"test://Ball", "pattern"},
                    BadUri{"test://ball?width=abc", "width"}, BadUri{"test://?width=8", "width"},
                    BadUri{"test://?height=12x", "height"}, BadUri{"test://?fps=0", "fps"},
                    BadUri{"test://?fps=fast", "fps"}, BadUri{"test://?is-live=maybe", "is-live"},
                    BadUri{"test://?colour=red", "colour"}, BadUri{"test://?width", "width"},
                    BadUri{"test://?width=64&width=32", "width"},
                    BadUri{"test://?error-after=-1", "error-after"},
                    BadUri{"test://?stall-after=3", "stall-after"},
                    BadUri{"test://?stall-ms=100", "stall-after"},
                    BadUri{"test://?num-buffers=0", "num-buffers"}));

}  // namespace
}  // namespace rtmot::platform
