#include "outputs/rtsp_video_server.hpp"

#include <fmt/format.h>
#include <gst/app/gstappsrc.h>
#include <gst/rtsp-server/rtsp-server.h>
#include <spdlog/spdlog.h>

#include <cmath>

#include "common/input_error.hpp"
#include "outputs/bgr_buffer.hpp"
#include "outputs/encoder_padding.hpp"
#include "platform/gst_ptr.hpp"

namespace rtmot::outputs {

RtspVideoServer::RtspVideoServer(VideoTarget target, double fps, const VideoEncoding& encoding)
    : target_(std::move(target)), fps_(fps > 0.0 ? fps : 30.0) {
  platform::gst::ensure_initialized();
  encoder_ = &open_encoder(target_.text, encoding);
  const VideoEncoder& encoder = *encoder_;
  context_ = g_main_context_new();
  loop_ = g_main_loop_new(context_, FALSE);
  server_ = gst_rtsp_server_new();
  gst_rtsp_server_set_address(server_, target_.host.c_str());
  const std::string service = std::to_string(target_.port);
  gst_rtsp_server_set_service(server_, service.c_str());

  GstRTSPMediaFactory* factory = gst_rtsp_media_factory_new();
  const int keyframe_interval = std::max(1, static_cast<int>(std::lround(fps_)));
  // The caps (frame size) are set on the appsrc, and the padding to a size the encoder takes on
  // the videobox, at the first frame it gets; do-timestamp stamps each buffer with the pipeline's
  // running time, as a live source does.
  const std::string launch = fmt::format(
      "( appsrc name=src format=time is-live=true do-timestamp=true block=false max-buffers=2 "
      "leaky-type=downstream ! videoconvert ! video/x-raw,format=I420 ! {}{}{} name=pay0 pt=96 "
      "config-interval=1 )",
      kSizedLaterPadding, encoder_launch(encoder, encoding.bitrate_kbps, keyframe_interval, true),
      rtp_payloader(encoder.codec));
  gst_rtsp_media_factory_set_launch(factory, launch.c_str());
  gst_rtsp_media_factory_set_shared(factory, TRUE);
  g_signal_connect(factory, "media-configure", G_CALLBACK(&RtspVideoServer::on_media_configure),
                   this);
  GstRTSPMountPoints* mounts = gst_rtsp_server_get_mount_points(server_);
  gst_rtsp_mount_points_add_factory(mounts, target_.mount.c_str(), factory);  // takes factory
  g_object_unref(mounts);

  source_id_ = gst_rtsp_server_attach(server_, context_);
  if (source_id_ == 0) {
    g_object_unref(server_);
    g_main_loop_unref(loop_);
    g_main_context_unref(context_);
    throw InputError(target_.text, 0, "output.video_file",
                     "cannot listen for RTSP clients on " + service + " (port in use?)",
                     ExitCode::network);
  }
  loop_thread_ = std::thread([this] {
    g_main_context_push_thread_default(context_);
    g_main_loop_run(loop_);
    g_main_context_pop_thread_default(context_);
  });
  spdlog::info("video: serving rtsp://{}:{}{}", target_.host == "0.0.0.0" ? "HOST" : target_.host,
               target_.port, target_.mount);
}

RtspVideoServer::~RtspVideoServer() {
  close();
}

void RtspVideoServer::close() {
  if (closed_) return;
  closed_ = true;
  g_main_loop_quit(loop_);
  loop_thread_.join();
  {
    const std::lock_guard<std::mutex> lock(media_mutex_);
    forget_media();
  }
  GSource* source = g_main_context_find_source_by_id(context_, source_id_);
  if (source != nullptr) g_source_destroy(source);
  g_object_unref(server_);
  g_main_loop_unref(loop_);
  g_main_context_unref(context_);
}

bool RtspVideoServer::has_client() {
  const std::lock_guard<std::mutex> lock(media_mutex_);
  return appsrc_ != nullptr;
}

void RtspVideoServer::on_media_configure(GstRTSPMediaFactory*, GstRTSPMedia* media, gpointer self) {
  auto& server = *static_cast<RtspVideoServer*>(self);
  GstElement* element = gst_rtsp_media_get_element(media);
  GstElement* appsrc = gst_bin_get_by_name_recurse_up(GST_BIN(element), "src");
  GstElement* padding = gst_bin_get_by_name_recurse_up(GST_BIN(element), "pad");
  gst_object_unref(element);
  g_signal_connect(media, "unprepared", G_CALLBACK(&RtspVideoServer::on_media_unprepared), self);
  const std::lock_guard<std::mutex> lock(server.media_mutex_);
  server.forget_media();
  server.appsrc_ = appsrc;
  server.padding_ = padding;
  server.caps_set_ = false;
  if (appsrc != nullptr) {
    server.probed_pad_ = gst_element_get_static_pad(appsrc, "src");
    if (server.probed_pad_ != nullptr) {
      server.probe_id_ = gst_pad_add_probe(server.probed_pad_, GST_PAD_PROBE_TYPE_BUFFER,
                                           &RtspVideoServer::on_frame_streamed, self, nullptr);
    }
  }
}

void RtspVideoServer::on_media_unprepared(GstRTSPMedia*, gpointer self) {
  auto& server = *static_cast<RtspVideoServer*>(self);
  const std::lock_guard<std::mutex> lock(server.media_mutex_);
  server.forget_media();
}

GstPadProbeReturn RtspVideoServer::on_frame_streamed(GstPad*, GstPadProbeInfo*, gpointer self) {
  static_cast<RtspVideoServer*>(self)->frames_streamed_.fetch_add(1, std::memory_order_relaxed);
  return GST_PAD_PROBE_OK;
}

// The probe goes with the media: a media that outlives this server (a client still holding it)
// must not call back into it.
void RtspVideoServer::forget_media() {
  if (probed_pad_ != nullptr) {
    if (probe_id_ != 0) gst_pad_remove_probe(probed_pad_, probe_id_);
    gst_object_unref(probed_pad_);
  }
  probed_pad_ = nullptr;
  probe_id_ = 0;
  if (appsrc_ != nullptr) gst_object_unref(appsrc_);
  if (padding_ != nullptr) gst_object_unref(padding_);
  appsrc_ = nullptr;
  padding_ = nullptr;
}

void RtspVideoServer::push(const cv::Mat& bgr) {
  if (closed_ || bgr.empty()) return;
  std::unique_lock<std::mutex> lock(media_mutex_, std::try_to_lock);
  if (!lock.owns_lock() || appsrc_ == nullptr) return;
  if (!caps_set_) {
    int numerator = 0;
    int denominator = 1;
    gst_util_double_to_fraction(fps_, &numerator, &denominator);
    const platform::gst::CapsPtr caps(gst_caps_new_simple(
        "video/x-raw", "format", G_TYPE_STRING, "BGR", "width", G_TYPE_INT, bgr.cols, "height",
        G_TYPE_INT, bgr.rows, "framerate", GST_TYPE_FRACTION, numerator, denominator, nullptr));
    // Before the first buffer: the videobox is sized before the encoder's caps are negotiated.
    if (padding_ != nullptr) set_encoder_padding(padding_, encoder_->codec, bgr.cols, bgr.rows);
    gst_app_src_set_caps(GST_APP_SRC(appsrc_), caps.get());
    caps_set_ = true;
    if (!padding_warned_) warn_if_padded(target_.text, *encoder_, bgr.cols, bgr.rows);
    padding_warned_ = true;
  }
  GstBuffer* buffer = copy_to_gst_buffer(bgr);
  ++frames_;
  // A refused buffer (client just left, media flushing) is simply not streamed.
  gst_app_src_push_buffer(GST_APP_SRC(appsrc_), buffer);
}

}  // namespace rtmot::outputs
