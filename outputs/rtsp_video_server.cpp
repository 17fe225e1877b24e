#include "outputs/rtsp_video_server.hpp"

#include <fmt/format.h>
#include <gst/app/gstappsrc.h>
#include <gst/rtsp-server/rtsp-server.h>
#include <spdlog/spdlog.h>

#include <atomic>
#include <cmath>
#include <mutex>

#include "common/input_error.hpp"
#include "outputs/bgr_buffer.hpp"
#include "outputs/encoder_padding.hpp"
#include "platform/gst_ptr.hpp"

namespace rtmot::outputs {

// What the media's callbacks share with the server: the current media's appsrc (set and cleared
// on gst-rtsp-server's threads, used by push() on the sink stage) and the frame count. Every
// closure and pad probe that calls back holds its own reference, so a callback that comes after
// the server is gone finds live memory. That happens: clients are served on gst-rtsp-server's
// thread pool, not on the server's main loop, and a client's teardown can unprepare the media
// after close() returned (CI once aborted there, std::system_error from locking the mutex of a
// server already destroyed).
struct RtspMediaLink {
  // push() only try_locks it: the sink stage never waits for an RTSP thread.
  std::mutex mutex;
  const GstRTSPMedia* media{nullptr};  // the current media, for identity only (not owned)
  GstElement* appsrc{nullptr};
  GstElement* padding{nullptr};  // the media's videobox: sized at its first frame
  GstPad* probed_pad{nullptr};   // the appsrc's src pad, while the probe counts its buffers
  gulong probe_id{0};
  bool caps_set{false};
  bool closed{false};  // the server closed: a media configured later gets no frames
  // Written by the media's streaming thread, read by anyone: a statistic, no other memory is
  // published through it, so relaxed order is enough.
  std::atomic<std::uint64_t> frames_streamed{0};

  // With `mutex` held. The probe goes with the media, and the elements' references are dropped.
  void forget() {
    if (probed_pad != nullptr) {
      if (probe_id != 0) gst_pad_remove_probe(probed_pad, probe_id);
      gst_object_unref(probed_pad);
    }
    probed_pad = nullptr;
    probe_id = 0;
    if (appsrc != nullptr) gst_object_unref(appsrc);
    if (padding != nullptr) gst_object_unref(padding);
    appsrc = nullptr;
    padding = nullptr;
    media = nullptr;
  }
};

namespace {

using LinkRef = std::shared_ptr<RtspMediaLink>;

// A callback's own reference, freed by GLib when the handler or probe goes.
gpointer new_link_ref(const LinkRef& link) {
  return new LinkRef(link);
}
void free_link_ref(gpointer data) {
  delete static_cast<LinkRef*>(data);
}
void free_link_ref_closure(gpointer data, GClosure*) {
  free_link_ref(data);
}

GstPadProbeReturn on_frame_streamed(GstPad*, GstPadProbeInfo*, gpointer data) {
  (*static_cast<LinkRef*>(data))->frames_streamed.fetch_add(1, std::memory_order_relaxed);
  return GST_PAD_PROBE_OK;
}

void on_media_unprepared(GstRTSPMedia* media, gpointer data) {
  const LinkRef link = *static_cast<LinkRef*>(data);  // alive past forget()'s own releases
  const std::lock_guard<std::mutex> lock(link->mutex);
  // A media replaced by a newer one (a client that left after another came) leaves the newer be.
  if (link->media == media) link->forget();
}

void on_media_configure(GstRTSPMediaFactory*, GstRTSPMedia* media, gpointer data) {
  const LinkRef link = *static_cast<LinkRef*>(data);
  GstElement* element = gst_rtsp_media_get_element(media);
  GstElement* appsrc = gst_bin_get_by_name_recurse_up(GST_BIN(element), "src");
  GstElement* padding = gst_bin_get_by_name_recurse_up(GST_BIN(element), "pad");
  gst_object_unref(element);
  g_signal_connect_data(media, "unprepared", G_CALLBACK(&on_media_unprepared), new_link_ref(link),
                        &free_link_ref_closure, GConnectFlags{});
  const std::lock_guard<std::mutex> lock(link->mutex);
  if (link->closed) {
    if (appsrc != nullptr) gst_object_unref(appsrc);
    if (padding != nullptr) gst_object_unref(padding);
    return;
  }
  link->forget();
  link->media = media;
  link->appsrc = appsrc;
  link->padding = padding;
  link->caps_set = false;
  if (appsrc != nullptr) {
    link->probed_pad = gst_element_get_static_pad(appsrc, "src");
    if (link->probed_pad != nullptr) {
      link->probe_id = gst_pad_add_probe(link->probed_pad, GST_PAD_PROBE_TYPE_BUFFER,
                                         &on_frame_streamed, new_link_ref(link), &free_link_ref);
    }
  }
}

GstRTSPFilterResult hang_up(GstRTSPServer*, GstRTSPClient*, gpointer) {
  return GST_RTSP_FILTER_REMOVE;  // closes the client's connection and its sessions
}

}  // namespace

RtspVideoServer::RtspVideoServer(VideoTarget target, double fps, const VideoEncoding& encoding)
    : target_(std::move(target)),
      fps_(fps > 0.0 ? fps : 30.0),
      link_(std::make_shared<RtspMediaLink>()) {
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
  g_signal_connect_data(factory, "media-configure", G_CALLBACK(&on_media_configure),
                        new_link_ref(link_), &free_link_ref_closure, GConnectFlags{});
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
  {
    const std::lock_guard<std::mutex> lock(link_->mutex);
    link_->closed = true;
    link_->forget();
  }
  // Clients are served on gst-rtsp-server's own threads, which outlive this server's main loop: a
  // client left connected would wait for frames until its own timeout. Hung up, it hears the end.
  gst_rtsp_server_client_filter(server_, &hang_up, nullptr);
  g_main_loop_quit(loop_);
  loop_thread_.join();
  GSource* source = g_main_context_find_source_by_id(context_, source_id_);
  if (source != nullptr) g_source_destroy(source);
  g_object_unref(server_);
  g_main_loop_unref(loop_);
  g_main_context_unref(context_);
}

bool RtspVideoServer::has_client() {
  const std::lock_guard<std::mutex> lock(link_->mutex);
  return link_->appsrc != nullptr;
}

std::uint64_t RtspVideoServer::frames_streamed() const {
  return link_->frames_streamed.load(std::memory_order_relaxed);
}

void RtspVideoServer::push(const cv::Mat& bgr) {
  if (closed_ || bgr.empty()) return;
  RtspMediaLink& link = *link_;
  std::unique_lock<std::mutex> lock(link.mutex, std::try_to_lock);
  if (!lock.owns_lock() || link.appsrc == nullptr) return;
  if (!link.caps_set) {
    int numerator = 0;
    int denominator = 1;
    gst_util_double_to_fraction(fps_, &numerator, &denominator);
    const platform::gst::CapsPtr caps(gst_caps_new_simple(
        "video/x-raw", "format", G_TYPE_STRING, "BGR", "width", G_TYPE_INT, bgr.cols, "height",
        G_TYPE_INT, bgr.rows, "framerate", GST_TYPE_FRACTION, numerator, denominator, nullptr));
    // Before the first buffer: the videobox is sized before the encoder's caps are negotiated.
    if (link.padding != nullptr) {
      set_encoder_padding(link.padding, encoder_->codec, bgr.cols, bgr.rows);
    }
    gst_app_src_set_caps(GST_APP_SRC(link.appsrc), caps.get());
    link.caps_set = true;
    if (!padding_warned_) warn_if_padded(target_.text, *encoder_, bgr.cols, bgr.rows);
    padding_warned_ = true;
  }
  // A refused buffer (client just left, media flushing) is simply not streamed.
  gst_app_src_push_buffer(GST_APP_SRC(link.appsrc), copy_to_gst_buffer(bgr));
}

}  // namespace rtmot::outputs
