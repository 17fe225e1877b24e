#include "outputs/video_target.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "common/input_error.hpp"
#include "common/output_open.hpp"
#include "common/stale_temporaries.hpp"
#include "platform/host_port.hpp"

namespace rtmot::outputs {
namespace {

bool starts_with(const std::string& text, const std::string& prefix) {
  return text.compare(0, prefix.size(), prefix) == 0;
}

bool ends_with(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() &&
         text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::optional<VideoTarget> parse_file(const std::string& text, std::string path,
                                      std::string& problem) {
  VideoTarget target;
  target.text = text;
  if (ends_with(path, ".mp4")) {
    target.kind = VideoTargetKind::mp4_file;
  } else if (ends_with(path, ".mkv")) {
    target.kind = VideoTargetKind::mkv_file;
  } else {
    problem = "a video file must end in .mp4 or .mkv (H.264), got '" + path + "'";
    return std::nullopt;
  }
  target.path = std::move(path);
  return target;
}

std::optional<VideoTarget> parse_rtsp(const std::string& text, std::string& problem) {
  const std::string rest = text.substr(std::string("rtsp://").size());
  const auto slash = rest.find('/');
  if (slash == std::string::npos || slash + 1 == rest.size()) {
    problem = "expected rtsp://[ADDRESS]:PORT/NAME";
    return std::nullopt;
  }
  VideoTarget target;
  target.kind = VideoTargetKind::rtsp;
  target.text = text;
  target.mount = rest.substr(slash);
  std::string address = rest.substr(0, slash);
  if (!address.empty() && address.front() == ':') address = "0.0.0.0" + address;  // rtsp://:8554/x
  const auto parsed = platform::parse_host_port(address, problem, 8554);
  if (!parsed) return std::nullopt;
  target.host = parsed->host;
  target.port = parsed->port;
  return target;
}

}  // namespace

std::optional<VideoTarget> parse_video_target(const std::string& text, std::string& problem) {
  if (text.empty()) {
    problem = "empty video target";
    return std::nullopt;
  }
  if (starts_with(text, "rtsp://")) return parse_rtsp(text, problem);
  if (starts_with(text, "rtp://")) {
    const auto parsed = platform::parse_host_port(text.substr(6), problem);
    if (!parsed) return std::nullopt;
    VideoTarget target;
    target.kind = VideoTargetKind::rtp;
    target.text = text;
    target.host = parsed->host;
    target.port = parsed->port;
    return target;
  }
  if (starts_with(text, "display://")) {
    const std::string number = text.substr(10);
    if (number.empty() || number.size() > 3 ||
        number.find_first_not_of("0123456789") != std::string::npos) {
      problem = "expected display://N";
      return std::nullopt;
    }
    VideoTarget target;
    target.kind = VideoTargetKind::display;
    target.text = text;
    target.display = std::stoi(number);
    return target;
  }
  if (starts_with(text, "file://")) return parse_file(text, text.substr(7), problem);
  if (text.find("://") != std::string::npos) {
    problem = "unknown scheme (file path, file://, rtsp://, rtp://, display://)";
    return std::nullopt;
  }
  return parse_file(text, text, problem);
}

std::string prepare_video_file(const VideoTarget& target) {
  const std::filesystem::path path(target.path);
  std::error_code error;
  if (path.has_parent_path()) {
    std::filesystem::create_directories(path.parent_path(), error);
    if (error)
      return "cannot create folder " + path.parent_path().string() + ": " + error.message();
  }
  if (std::filesystem::is_directory(path, error)) return "is a directory";
  // A muxer seeks back into its file (mp4's index, mkv's cues and duration): a FIFO, socket or
  // block device cannot be one (a FIFO with no reader blocked filesink's open() for ever). A
  // character device (/dev/null, /dev/full) is written in place.
  struct stat status {};
  if (::stat(path.c_str(), &status) == 0 && !S_ISREG(status.st_mode) && !S_ISCHR(status.st_mode)) {
    return std::string(S_ISFIFO(status.st_mode) ? "is a FIFO" : "is not a regular file") +
           ": a video file is seeked back into as it is finished (stream it with rtp:// or "
           "rtsp:// instead)";
  }
  // The writer writes PATH.tmp-PID and renames it to PATH when the video is finished: that
  // temporary is created (and removed) now, so that what fails here fails before the run, and an
  // existing PATH is left as it is until a finished video replaces it.
  try {
    ::close(create_temporary(path));
  } catch (const InputError& refused) {
    return refused.problem();
  }
  ::unlink(temporary_path_for(path).c_str());
  return "";
}

std::string rtp_sdp(const VideoTarget& target, VideoCodec codec) {
  // RFC 4566 session, RFC 6184 (H.264) or RFC 7798 (H.265) payload; the receiver listens on the
  // port we send to.
  const bool v6 = target.host.find(':') != std::string::npos;
  const char* family = v6 ? "IP6" : "IP4";
  return "v=0\n"
         "o=- 0 0 IN " +
         std::string(family) + " " + target.host + "\n" +
         "s=rtmot annotated video\n"
         "c=IN " +
         family + " " + target.host + "\n" +
         "t=0 0\n"
         "m=video " +
         std::to_string(target.port) + " RTP/AVP 96\n" + "a=rtpmap:96 " +
         std::string(rtp_encoding_name(codec)) + "/90000\n" +
         (codec == VideoCodec::h264 ? "a=fmtp:96 packetization-mode=1\n" : "");
}

}  // namespace rtmot::outputs
