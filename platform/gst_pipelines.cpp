#include "platform/gst_pipelines.hpp"

#include "common/input_error.hpp"
#include "platform/gst_ptr.hpp"

namespace rtmot::platform::gst {
namespace {

constexpr const char* to_bgr_appsink = "videoconvert ! video/x-raw,format=BGR ! appsink name=sink";

ObjectPtr<GstElement> element(GstBin& pipeline, const char* name) {
  ObjectPtr<GstElement> found(gst_bin_get_by_name(&pipeline, name));
  if (!found) throw std::logic_error(std::string("pipeline has no element named ") + name);
  return found;
}

void add_size_and_rate(GstCaps* caps, int width, int height, double fps) {
  if (width > 0) gst_caps_set_simple(caps, "width", G_TYPE_INT, width, nullptr);
  if (height > 0) gst_caps_set_simple(caps, "height", G_TYPE_INT, height, nullptr);
  if (fps > 0.0) {
    int numerator = 0;
    int denominator = 1;
    gst_util_double_to_fraction(fps, &numerator, &denominator);
    gst_caps_set_simple(caps, "framerate", GST_TYPE_FRACTION, numerator, denominator, nullptr);
  }
}

// Cameras deliver raw video or MJPEG; the request applies to whichever the camera offers.
CapsPtr camera_request(SourceKind kind, const SourceOptions& options) {
  if (kind == SourceKind::csi) {
    CapsPtr caps(gst_caps_from_string("video/x-raw(memory:NVMM)"));
    add_size_and_rate(caps.get(), options.width, options.height, options.fps);
    return caps;
  }
  CapsPtr raw(gst_caps_new_empty_simple("video/x-raw"));
  add_size_and_rate(raw.get(), options.width, options.height, options.fps);
  GstCaps* jpeg = gst_caps_new_empty_simple("image/jpeg");
  add_size_and_rate(jpeg, options.width, options.height, options.fps);
  return CapsPtr(gst_caps_merge(raw.release(), jpeg));
}

void configure_test(GstBin& pipeline, const VideoUri& uri) {
  const TestSourceParams& test = uri.test;
  const auto source = element(pipeline, "src");
  GParamSpec* spec = g_object_class_find_property(G_OBJECT_GET_CLASS(source.get()), "pattern");
  const GEnumValue* pattern =
      g_enum_get_value_by_nick(G_PARAM_SPEC_ENUM(spec)->enum_class, test.pattern.c_str());
  if (pattern == nullptr) {
    throw InputError(uri.text, 0, "pattern",
                     "unknown videotestsrc pattern '" + test.pattern +
                         "' (e.g. smpte, ball, snow, black, white, gradient)",
                     ExitCode::source_failed);
  }
  // videotestsrc's num-buffers ends the stream with end-of-stream, which is what eos-after means.
  int num_buffers = test.num_buffers;
  if (test.eos_after >= 0 && (num_buffers < 0 || test.eos_after < num_buffers)) {
    num_buffers = test.eos_after;
  }
  g_object_set(source.get(), "pattern", pattern->value, "is-live", gboolean{test.is_live},
               "num-buffers", num_buffers, nullptr);

  CapsPtr caps(gst_caps_new_empty_simple("video/x-raw"));
  add_size_and_rate(caps.get(), test.width, test.height, test.fps);
  g_object_set(element(pipeline, "request").get(), "caps", caps.get(), nullptr);

  // identity fails *on* its error-after'th buffer, so N frames get through with N + 1.
  if (test.error_after >= 0) {
    g_object_set(element(pipeline, "faults").get(), "error-after", test.error_after + 1, nullptr);
  }
}

}  // namespace

std::string pipeline_description(SourceKind kind) {
  const std::string tail = std::string(" ! ") + to_bgr_appsink;
  switch (kind) {
    case SourceKind::file:
      return "filesrc name=src ! decodebin" + tail;
    case SourceKind::v4l2:
      return "v4l2src name=src ! capsfilter name=request ! decodebin" + tail;
    case SourceKind::csi:
      return "nvarguscamerasrc name=src ! capsfilter name=request ! nvvidconv ! "
             "video/x-raw,format=BGRx" +
             tail;
    case SourceKind::rtsp:
      // Only the video stream is linked; rtspsrc carries on with audio streams left unlinked.
      return "rtspsrc name=src ! application/x-rtp,media=video ! decodebin" + tail;
    case SourceKind::test:
      return "videotestsrc name=src ! capsfilter name=request ! identity name=faults" + tail;
    case SourceKind::images:
      break;  // not GStreamer: platform/image_folder_source.hpp
  }
  throw std::logic_error("unknown source kind");
}

void configure_pipeline(GstBin& pipeline, const VideoUri& uri, const SourceOptions& options) {
  switch (uri.kind) {
    case SourceKind::file:
      g_object_set(element(pipeline, "src").get(), "location", uri.location.c_str(), nullptr);
      break;
    case SourceKind::v4l2:
      g_object_set(element(pipeline, "src").get(), "device", uri.location.c_str(), nullptr);
      g_object_set(element(pipeline, "request").get(), "caps",
                   camera_request(uri.kind, options).get(), nullptr);
      break;
    case SourceKind::csi:
      g_object_set(element(pipeline, "src").get(), "sensor-id", uri.sensor_id, nullptr);
      g_object_set(element(pipeline, "request").get(), "caps",
                   camera_request(uri.kind, options).get(), nullptr);
      break;
    case SourceKind::rtsp:
      g_object_set(element(pipeline, "src").get(), "location", uri.location.c_str(), "latency",
                   static_cast<guint>(options.rtsp_latency_ms), nullptr);
      break;
    case SourceKind::test:
      configure_test(pipeline, uri);
      break;
    case SourceKind::images:
      throw std::logic_error("images:// is not a GStreamer source");
  }

  const bool live = is_live(uri);
  // Files: every frame, with back-pressure (a small queue, never dropping). Live: only the newest
  // frame waits for us; older ones are dropped so latency never builds up.
  g_object_set(element(pipeline, "sink").get(), "sync", FALSE, "drop", gboolean{live},
               "max-buffers", live ? 1u : 2u, "emit-signals", FALSE, nullptr);
}

}  // namespace rtmot::platform::gst
