#pragma once
// A video-source URI taken apart into what the capture code needs. Parsing needs no GStreamer, so
// it is cheap to test and to validate command lines with.
#include <string>
#include <string_view>

#include "tracker/enum_names.hpp"

namespace rtmot::platform {

enum class SourceKind { file, v4l2, csi, rtsp, test, images };
/// The one table of source kinds, named by their URI schemes (parsing, messages, logs). rtsps (RTSP
/// over TLS) is a second name of rtsp, after it, so that a kind's name is its first.
inline constexpr auto kSourceSchemes =
    tracker::make_enum_names<SourceKind>(std::pair{SourceKind::file, std::string_view("file")},
                                         std::pair{SourceKind::v4l2, std::string_view("v4l2")},
                                         std::pair{SourceKind::csi, std::string_view("csi")},
                                         std::pair{SourceKind::rtsp, std::string_view("rtsp")},
                                         std::pair{SourceKind::rtsp, std::string_view("rtsps")},
                                         std::pair{SourceKind::test, std::string_view("test")},
                                         std::pair{SourceKind::images, std::string_view("images")});

/// test://PATTERN?key=value&... : GStreamer's videotestsrc plus injected faults. -1 means "off".
struct TestSourceParams {
  std::string pattern{"smpte"};  // a videotestsrc pattern nick (smpte, ball, snow, black, ...)
  int width{320};
  int height{240};
  double fps{30.0};
  int num_buffers{-1};  // videotestsrc's own limit; ends with end-of-stream
  bool is_live{false};  // live: produced at `fps` in real time, only the newest frame handed over
  int error_after{-1};  // the source fails (GStreamer error) after this many frames
  int stall_after{-1};  // the source stops producing for `stall_ms` after this many frames
  int stall_ms{0};
  int eos_after{-1};  // the source ends (end-of-stream) after this many frames
};

/// images://DIR?fps=N&loop=K (platform/image_folder_source.hpp); a plain path to a folder too.
struct ImageFolderParams {
  double fps{30.0};  // the rate the frames' pts follow (jetson-inference's default)
  int loop{1};       // plays the folder this many times (benchmarks on a few files)
};

/// file://PATH?fps=N: a recording whose header's rate is wrong (PETS09-S2L1's vtest.avi says 10
/// fps, its scene was filmed at 7) plays at N: frame i is timed at i / N, whatever the file's own
/// timestamps say, so simulated playback, latency and the tracker's clock all follow the true rate.
struct RecordingParams {
  double fps{0.0};  // 0: the file's own timestamps and rate
};

struct VideoUri {
  std::string text;  // as the user wrote it
  SourceKind kind{SourceKind::file};
  std::string location;  // file path, v4l2 device, or the full rtsp:// URL
  int sensor_id{0};      // csi://N
  TestSourceParams test;
  ImageFolderParams images;
  RecordingParams recording;  // file:// only
};

/// Throws rtmot::InputError (ExitCode::source_failed) naming the URI and the offending part.
VideoUri parse_video_uri(const std::string& uri);

/// Cameras, streams and live test sources deliver frames in real time (and drop old ones).
bool is_live(const VideoUri& uri);

/// "file://, v4l2://, csi://, rtsp://, rtsps://, test://, images://": kSourceSchemes as URI
/// prefixes, for help texts and docs/config.md.
std::string source_uri_schemes();

/// The kind's scheme name (kSourceSchemes).
const char* to_string(SourceKind kind);

}  // namespace rtmot::platform
