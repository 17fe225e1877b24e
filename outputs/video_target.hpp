#pragma once
// Where the annotated video goes, by URI (jetson-inference style):
//   out/demo.mp4, file://out/demo.mkv   H.264 in MP4 (moov first: plays in a browser) or Matroska
//   rtsp://[ADDRESS]:PORT/NAME           served by gst-rtsp-server (clients pull it)
//   rtp://HOST:PORT                      RTP/UDP pushed to one receiver
//   display://N                          a window on display N (where a display exists)
#include <cstdint>
#include <optional>
#include <string>

#include "outputs/video_encoding.hpp"

namespace rtmot::outputs {

enum class VideoTargetKind { mp4_file, mkv_file, rtsp, rtp, display };

struct VideoTarget {
  VideoTargetKind kind{VideoTargetKind::mp4_file};
  std::string text;  // as given, for messages
  std::string path;  // files
  std::string host;  // rtp: destination; rtsp: address to listen on ("" = every address)
  std::uint16_t port{0};
  std::string mount;  // rtsp: "/NAME"
  int display{0};
};

/// Parses `text`; nullopt with `problem` set (one phrase) if malformed.
std::optional<VideoTarget> parse_video_target(const std::string& text, std::string& problem);

/// The SDP a player needs for an rtp:// target (H.264 or H.265, payload type 96, as our payloader
/// sends):
/// save it as FILE.sdp and `ffplay -protocol_whitelist file,udp,rtp FILE.sdp` (or VLC) plays the
/// stream. Lines end with "\n".
std::string rtp_sdp(const VideoTarget& target, VideoCodec codec = VideoCodec::h264);

/// For a file target: creates its missing folders and checks that the file can be created and
/// written (a temporary beside it is created and removed; an existing file is left until the
/// finished video replaces it). Returns "" or the reason it cannot
/// ("permission denied", "is a directory", ...). Run before the model loads: a typo costs nothing.
std::string prepare_video_file(const VideoTarget& target);

}  // namespace rtmot::outputs
