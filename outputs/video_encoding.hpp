#pragma once
// How the annotated video is encoded: the codec (H.264 or H.265), the encoder element and the
// bitrate (output.video_codec, output.video_encoder, output.video_bitrate: docs/config.md). One
// table of the encoders we know, in the order `auto` prefers them: a board's hardware encoder
// where its GStreamer has one (nvv4l2h264enc on Jetson, v4l2h264enc on boards with a V4L2
// memory-to-memory encoder such as the Raspberry Pi 4), else the software one.
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "tracker/enum_names.hpp"

namespace rtmot::outputs {

enum class VideoCodec { h264, h265 };
inline constexpr auto kVideoCodecNames =
    tracker::make_enum_names<VideoCodec>(std::pair{VideoCodec::h264, std::string_view("h264")},
                                         std::pair{VideoCodec::h265, std::string_view("h265")});

/// "H.264" or "H.265", for messages.
std::string_view codec_title(VideoCodec codec);

/// The documented bitrate range, kbit/s.
inline constexpr int kMinVideoBitrateKbps = 64;
inline constexpr int kMaxVideoBitrateKbps = 200'000;
/// x264enc's own default, what every video was written at before the setting existed.
inline constexpr int kDefaultVideoBitrateKbps = 2048;

struct VideoEncoding {
  VideoCodec codec{VideoCodec::h264};
  /// auto, hardware, software, or an element of video_encoders() (parse_encoder_request).
  std::string encoder{"auto"};
  int bitrate_kbps{kDefaultVideoBitrateKbps};
};

struct VideoEncoder {
  std::string_view element;  // the GStreamer element
  VideoCodec codec;
  bool hardware;
  std::string_view found_in;  // where a user gets it (a Debian package, the board's BSP)
};

/// Every encoder we know, in auto's order of preference per codec (hardware first).
const std::vector<VideoEncoder>& video_encoders();

/// "auto, hardware, software or an encoder element (nvv4l2h264enc, ...)", for help and errors.
std::string encoder_request_alternatives();

/// `text` if it is auto, hardware, software or an element of video_encoders(); nullopt and
/// `problem` (with the nearest valid name) otherwise.
std::optional<std::string> parse_encoder_request(const std::string& text, std::string& problem);

/// Whether this GStreamer has an element (a factory of that name).
using HasElement = std::function<bool(std::string_view element)>;

struct EncoderChoice {
  const VideoEncoder* encoder{nullptr};  // nullptr: none fits; `problem` says why
  std::string why;                       // for the start-up log line
  std::string problem;
};

/// The encoder for `encoding`: the element it names, or the first present one of its codec that
/// the request allows (auto: hardware first; hardware/software: those only). A hardware encoder
/// also needs its converter (nvvidconv for nvv4l2*). `has` is the GStreamer registry, or a
/// stand-in in tests.
EncoderChoice choose_encoder(const VideoEncoding& encoding, const HasElement& has);

/// The elements the choice needs besides the encoder (its converter, the stream parser).
std::vector<std::string_view> encoder_companions(const VideoEncoder& encoder);

/// The encoding part of a pipeline description, from I420 frames to a parsed elementary stream
/// (what a muxer or payloader takes), ending in "! ". `live`: low latency (no lookahead, no
/// B-frames) for streams; a file favours quality at the same bitrate.
std::string encoder_launch(const VideoEncoder& encoder, int bitrate_kbps, int keyframe_interval,
                           bool live);

/// The RTP payloader of the codec ("rtph264pay"/"rtph265pay") and its SDP encoding name.
std::string_view rtp_payloader(VideoCodec codec);
std::string_view rtp_encoding_name(VideoCodec codec);

/// Whether this process's GStreamer has `element` (initialises GStreamer).
bool gstreamer_has(std::string_view element);

/// choose_encoder() on this GStreamer, for the output `output` (its URI, for messages): logs the
/// choice in one line ("video: H.264 by x264enc (software; auto: nvv4l2h264enc, v4l2h264enc
/// absent) at 2048 kbit/s -> out/demo.mp4"); throws InputError (exit 3, field
/// output.video_encoder) when none fits.
const VideoEncoder& open_encoder(const std::string& output, const VideoEncoding& encoding);

}  // namespace rtmot::outputs
