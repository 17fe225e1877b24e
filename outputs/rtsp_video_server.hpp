#pragma once
// rtsp://ADDRESS:PORT/NAME: an RTSP server (gst-rtsp-server) that clients pull the annotated video
// from. One shared media for every client: appsrc -> videobox (padding to a size the encoder takes,
// outputs/encoder_padding.hpp) -> the encoder (zero latency) -> rtph26Xpay. The
// server runs its own GLib main loop on a thread (it handles RTSP requests there); frames are only
// encoded while at least one client watches.
#include <gst/gst.h>

#include <cstdint>
#include <memory>
#include <thread>

#include "outputs/video_encoding.hpp"
#include "outputs/video_stream.hpp"

typedef struct _GstRTSPServer GstRTSPServer;
typedef struct _GstRTSPMedia GstRTSPMedia;
typedef struct _GstRTSPMediaFactory GstRTSPMediaFactory;

namespace rtmot::outputs {

struct RtspMediaLink;  // what the media's callbacks share with the server (the .cpp says why)

class RtspVideoServer final : public VideoStream {
 public:
  /// Listens at once; throws InputError (ExitCode::network) if the port cannot be bound.
  RtspVideoServer(VideoTarget target, double fps, const VideoEncoding& encoding = {});
  ~RtspVideoServer() override;
  RtspVideoServer(const RtspVideoServer&) = delete;
  RtspVideoServer& operator=(const RtspVideoServer&) = delete;

  /// Never waits: with no client, or when the RTSP thread holds the media for a moment, the frame
  /// is not streamed (a live stream shows the newest frame, it does not queue old ones).
  void push(const cv::Mat& bgr) override;
  void close() override;

  /// Whether a client is watching (its media is prepared): for tests and logs.
  bool has_client();
  /// Frames that left the appsrc into the encoder (counted by a pad probe): what a client that
  /// watched throughout received. Fewer than pushed when no client watched yet, or when the encoder
  /// fell behind and the two-frame leaky queue dropped the oldest (a live stream shows the newest).
  std::uint64_t frames_streamed() const override;

 private:
  VideoTarget target_;
  double fps_;
  const VideoEncoder* encoder_{nullptr};  // chosen in the constructor, for the padding
  GMainContext* context_{nullptr};
  GMainLoop* loop_{nullptr};
  GstRTSPServer* server_{nullptr};
  guint source_id_{0};
  std::thread loop_thread_;
  std::shared_ptr<RtspMediaLink> link_;
  bool padding_warned_{false};
  bool closed_{false};
};

}  // namespace rtmot::outputs
