#include "outputs/video_stream.hpp"

#include <gst/gst.h>

#include <cstdlib>
#include <filesystem>
#include <string_view>

#include "outputs/gst_video_output.hpp"
#include "outputs/rtsp_video_server.hpp"
#include "platform/gst_ptr.hpp"

namespace rtmot::outputs {
namespace {

// Which Debian package (all installed by scripts/install_deps.sh) holds each element we use
// besides the encoders (outputs/video_encoding.cpp says where each of those comes from).
std::string_view package_of(std::string_view element) {
  if (element == "ximagesink") return "gstreamer1.0-x";
  if (element == "appsrc" || element == "videoconvert") return "gstreamer1.0-plugins-base";
  if (element == "filesink") return "libgstreamer1.0-0";
  if (element == "h264parse" || element == "h265parse") return "gstreamer1.0-plugins-bad";
  return "gstreamer1.0-plugins-good";  // mp4mux, matroskamux, rtph26Xpay, udpsink
}

// A display:// window needs an X server (a desktop, or XWayland): its local socket is
// /tmp/.X11-unix/X<N>. Without it ximagesink fails only once the first frame is drawn.
std::string check_display(int display) {
  const std::filesystem::path socket = "/tmp/.X11-unix/X" + std::to_string(display);
  std::error_code error;
  if (std::filesystem::exists(socket, error)) return "";
  const char* env = std::getenv("DISPLAY");
  return "no display :" + std::to_string(display) + " to show the video on (no X server socket " +
         socket.string() + "; DISPLAY is " +
         (env != nullptr && *env != '\0' ? std::string("'") + env + "'" : std::string("unset")) +
         "): display:// needs a desktop session; without one write a file (out.mp4) or stream "
         "it (rtsp://:8554/NAME, rtp://HOST:PORT)";
}

}  // namespace

std::string check_video_elements(const VideoTarget& target, const VideoEncoding& encoding) {
  platform::gst::ensure_initialized();
  std::vector<std::string_view> needed = {"appsrc", "videoconvert"};
  if (target.kind != VideoTargetKind::display) {
    const EncoderChoice choice = choose_encoder(encoding, gstreamer_has);
    if (choice.encoder == nullptr) return choice.problem;
    needed.push_back("videobox");
    for (const auto companion : encoder_companions(*choice.encoder)) needed.push_back(companion);
  }
  switch (target.kind) {
    case VideoTargetKind::mp4_file:
      needed.insert(needed.end(), {"mp4mux", "filesink"});
      break;
    case VideoTargetKind::mkv_file:
      needed.insert(needed.end(), {"matroskamux", "filesink"});
      break;
    case VideoTargetKind::rtp:
    case VideoTargetKind::rtsp:
      needed.insert(needed.end(), {rtp_payloader(encoding.codec), "udpsink"});
      break;
    case VideoTargetKind::display:
      needed.push_back("ximagesink");
      break;
  }
  std::string missing;
  for (const auto name : needed) {
    if (!gstreamer_has(name)) {
      missing += (missing.empty() ? "" : ", ") + std::string(name) + " (in " +
                 std::string(package_of(name)) + ")";
    }
  }
  if (!missing.empty()) {
    return "this GStreamer lacks " + missing +
           ": apt-get install the package named, or run scripts/install_deps.sh";
  }
  return target.kind == VideoTargetKind::display ? check_display(target.display) : "";
}

std::unique_ptr<VideoStream> open_video_stream(const VideoTarget& target, double fps,
                                               const VideoEncoding& encoding) {
  if (target.kind == VideoTargetKind::rtsp) {
    return std::make_unique<RtspVideoServer>(target, fps, encoding);
  }
  return std::make_unique<GstVideoOutput>(target, fps, encoding);
}

}  // namespace rtmot::outputs
