#include "outputs/video_stream.hpp"

#include <gst/gst.h>

#include "outputs/gst_video_output.hpp"
#include "outputs/rtsp_video_server.hpp"
#include "platform/gst_ptr.hpp"

namespace rtmot::outputs {

std::string check_video_elements(const VideoTarget& target) {
  platform::gst::ensure_initialized();
  std::vector<const char*> needed = {"appsrc", "videoconvert"};
  switch (target.kind) {
    case VideoTargetKind::mp4_file:
      needed.insert(needed.end(), {"x264enc", "mp4mux", "filesink"});
      break;
    case VideoTargetKind::mkv_file:
      needed.insert(needed.end(), {"x264enc", "matroskamux", "filesink"});
      break;
    case VideoTargetKind::rtp:
    case VideoTargetKind::rtsp:
      needed.insert(needed.end(), {"x264enc", "rtph264pay", "udpsink"});
      break;
    case VideoTargetKind::display:
      needed.push_back("ximagesink");
      break;
  }
  std::string missing;
  for (const char* name : needed) {
    const platform::gst::ObjectPtr<GstElementFactory> factory{gst_element_factory_find(name)};
    if (!factory) missing += (missing.empty() ? "" : ", ") + std::string(name);
  }
  if (missing.empty()) return "";
  return "this GStreamer lacks " + missing +
         " (scripts/install_deps.sh installs the plugins: x264enc is in gstreamer1.0-plugins-ugly)";
}

std::unique_ptr<VideoStream> open_video_stream(const VideoTarget& target, double fps) {
  if (target.kind == VideoTargetKind::rtsp) return std::make_unique<RtspVideoServer>(target, fps);
  return std::make_unique<GstVideoOutput>(target, fps);
}

}  // namespace rtmot::outputs
