#include "outputs/video_encoding.hpp"

#include <fmt/format.h>
#include <gst/gst.h>
#include <spdlog/spdlog.h>

#include "common/input_error.hpp"
#include "common/nearest_name.hpp"
#include "platform/gst_ptr.hpp"

namespace rtmot::outputs {
namespace {

constexpr std::string_view kJetson = "NVIDIA's L4T GStreamer plugins (JetPack)";
constexpr std::string_view kV4l2 =
    "gstreamer1.0-plugins-good, with a V4L2 encoder device (/dev/video*: Raspberry Pi, i.MX, "
    "Rockchip...)";

std::vector<std::string> request_names() {
  std::vector<std::string> names = {"auto", "hardware", "software"};
  for (const auto& encoder : video_encoders()) names.emplace_back(encoder.element);
  return names;
}

// "nvv4l2h264enc (NVIDIA's ...), v4l2h264enc (...)": what was looked for and where it comes from.
std::string list_with_sources(const std::vector<const VideoEncoder*>& encoders) {
  std::string text;
  for (const auto* encoder : encoders) {
    text += (text.empty() ? "" : ", ") +
            fmt::format("{} (from {})", encoder->element, encoder->found_in);
  }
  return text;
}

std::string names_of(const std::vector<const VideoEncoder*>& encoders) {
  std::string text;
  for (const auto* encoder : encoders)
    text += (text.empty() ? "" : ", ") + std::string(encoder->element);
  return text;
}

bool has_all(const VideoEncoder& encoder, const HasElement& has) {
  if (!has(encoder.element)) return false;
  for (const auto companion : encoder_companions(encoder)) {
    if (!has(companion)) return false;
  }
  return true;
}

}  // namespace

std::string_view codec_title(VideoCodec codec) {
  return codec == VideoCodec::h264 ? "H.264" : "H.265";
}

const std::vector<VideoEncoder>& video_encoders() {
  static const std::vector<VideoEncoder> encoders = {
      {"nvv4l2h264enc", VideoCodec::h264, true, kJetson},
      {"v4l2h264enc", VideoCodec::h264, true, kV4l2},
      {"x264enc", VideoCodec::h264, false, "gstreamer1.0-plugins-ugly"},
      // Debian's OpenH264 (Cisco's BSD code): the H.264 software encoder where x264 is not
      // installed (plugins-ugly is left out of some images for its licence).
      {"openh264enc", VideoCodec::h264, false, "gstreamer1.0-plugins-bad"},
      {"nvv4l2h265enc", VideoCodec::h265, true, kJetson},
      {"v4l2h265enc", VideoCodec::h265, true, kV4l2},
      {"x265enc", VideoCodec::h265, false, "gstreamer1.0-plugins-bad"},
  };
  return encoders;
}

std::string encoder_request_alternatives() {
  std::string elements;
  for (const auto& encoder : video_encoders()) {
    elements += (elements.empty() ? "" : ", ") + std::string(encoder.element);
  }
  return "auto, hardware, software or an encoder element (" + elements + ")";
}

std::optional<std::string> parse_encoder_request(const std::string& text, std::string& problem) {
  const auto names = request_names();
  for (const auto& name : names) {
    if (name == text) return text;
  }
  std::string hint = did_you_mean(text, names);
  // The short names of GStreamer's docs and of other tools (x264, nvv4l2h264): the element is
  // NAME + "enc", too far for the edit distance on short names.
  if (hint.empty()) {
    for (const auto& encoder : video_encoders()) {
      if (encoder.element == text + "enc") hint = " (did you mean " + text + "enc?)";
    }
  }
  problem = "'" + text + "': expected " + encoder_request_alternatives() + hint;
  return std::nullopt;
}

std::vector<std::string_view> encoder_companions(const VideoEncoder& encoder) {
  std::vector<std::string_view> companions;
  // Jetson's encoders take frames in NVMM (device) memory only: nvvidconv copies them there.
  if (encoder.element.substr(0, 4) == "nvv4") companions.emplace_back("nvvidconv");
  companions.emplace_back(encoder.codec == VideoCodec::h264 ? "h264parse" : "h265parse");
  return companions;
}

EncoderChoice choose_encoder(const VideoEncoding& encoding, const HasElement& has) {
  EncoderChoice choice;
  const std::string_view codec = codec_title(encoding.codec);
  const auto& all = video_encoders();
  if (encoding.encoder != "auto" && encoding.encoder != "hardware" &&
      encoding.encoder != "software") {
    for (const auto& encoder : all) {
      if (encoder.element != encoding.encoder) continue;
      if (encoder.codec != encoding.codec) {
        choice.problem = fmt::format("{} encodes {}, not {} (output.video_codec, --video-codec)",
                                     encoder.element, codec_title(encoder.codec), codec);
      } else if (!has_all(encoder, has)) {
        std::string missing;
        if (!has(encoder.element)) {
          missing = fmt::format("{} (from {})", encoder.element, encoder.found_in);
        }
        for (const auto companion : encoder_companions(encoder)) {
          if (!has(companion)) missing += (missing.empty() ? "" : ", ") + std::string(companion);
        }
        choice.problem = "this GStreamer lacks " + missing;
      } else {
        choice.encoder = &encoder;
        choice.why = "asked for";
      }
      return choice;
    }
    choice.problem = "unknown encoder '" + encoding.encoder + "'";
    return choice;
  }
  std::vector<const VideoEncoder*> candidates;
  std::vector<const VideoEncoder*> absent;
  for (const auto& encoder : all) {
    if (encoder.codec != encoding.codec) continue;
    if (encoding.encoder == "hardware" && !encoder.hardware) continue;
    if (encoding.encoder == "software" && encoder.hardware) continue;
    candidates.push_back(&encoder);
    if (choice.encoder == nullptr && has_all(encoder, has)) {
      choice.encoder = &encoder;
    } else if (choice.encoder == nullptr) {
      absent.push_back(&encoder);
    }
  }
  if (choice.encoder == nullptr) {
    choice.problem = fmt::format("no {}{} encoder in this GStreamer: looked for {}",
                                 encoding.encoder == "auto" ? "" : encoding.encoder + " ", codec,
                                 list_with_sources(candidates));
    return choice;
  }
  if (absent.empty()) {
    choice.why = fmt::format("{}: the first of {}", encoding.encoder, names_of(candidates));
  } else {
    choice.why = fmt::format("{}: {} absent", encoding.encoder, names_of(absent));
  }
  return choice;
}

std::string encoder_launch(const VideoEncoder& encoder, int bitrate_kbps, int keyframe_interval,
                           bool live) {
  const std::string_view element = encoder.element;
  const bool h264 = encoder.codec == VideoCodec::h264;
  const std::string parse = h264 ? "h264parse ! " : "h265parse ! ";
  const long bits = static_cast<long>(bitrate_kbps) * 1000L;
  if (element == "x264enc") {
    // Browsers play H.264 High profile 4:2:0; a stream drops the lookahead and B-frames.
    return live ? fmt::format(
                      "x264enc speed-preset=ultrafast tune=zerolatency bitrate={} key-int-max={} "
                      "! {}",
                      bitrate_kbps, keyframe_interval, parse)
                : fmt::format(
                      "x264enc speed-preset=superfast bitrate={} key-int-max={} ! "
                      "video/x-h264,profile=high ! {}",
                      bitrate_kbps, keyframe_interval, parse);
  }
  if (element == "openh264enc") {
    // Its default is 128 kbit/s in "quality" mode: the bitrate is only kept in bitrate mode.
    // Frame skipping off: a file gets every frame.
    return fmt::format(
        "openh264enc rate-control=bitrate bitrate={} gop-size={} complexity={} "
        "enable-frame-skip=false ! {}",
        bits, keyframe_interval, live ? "low" : "medium", parse);
  }
  if (element == "x265enc") {
    return fmt::format("x265enc speed-preset={} {}bitrate={} key-int-max={} ! {}",
                       live ? "ultrafast" : "superfast", live ? "tune=zerolatency " : "",
                       bitrate_kbps, keyframe_interval, parse);
  }
  if (element == "nvv4l2h264enc" || element == "nvv4l2h265enc") {
    // SPS/PPS before every keyframe: a player joining a stream, or a cut file, can start there.
    return fmt::format(
        "nvvidconv ! video/x-raw(memory:NVMM),format=I420 ! {} bitrate={} iframeinterval={} "
        "insert-sps-pps=true ! {}",
        element, bits, keyframe_interval, parse);
  }
  // v4l2h264enc / v4l2h265enc: the driver's controls, by their V4L2 names.
  return fmt::format("{} extra-controls=\"controls,video_bitrate={}{}\" ! {}", element, bits,
                     h264 ? fmt::format(",h264_i_frame_period={}", keyframe_interval) : "", parse);
}

std::string_view rtp_payloader(VideoCodec codec) {
  return codec == VideoCodec::h264 ? "rtph264pay" : "rtph265pay";
}

std::string_view rtp_encoding_name(VideoCodec codec) {
  return codec == VideoCodec::h264 ? "H264" : "H265";
}

bool gstreamer_has(std::string_view element) {
  platform::gst::ensure_initialized();
  const platform::gst::ObjectPtr<GstElementFactory> factory{
      gst_element_factory_find(std::string(element).c_str())};
  return factory != nullptr;
}

const VideoEncoder& open_encoder(const std::string& output, const VideoEncoding& encoding) {
  const EncoderChoice choice = choose_encoder(encoding, gstreamer_has);
  if (choice.encoder == nullptr) {
    throw InputError(output, 0, "output.video_encoder", choice.problem);
  }
  spdlog::info("video: {} by {} ({}; {}) at {} kbit/s -> {}", codec_title(encoding.codec),
               choice.encoder->element, choice.encoder->hardware ? "hardware" : "software",
               choice.why, encoding.bitrate_kbps, output);
  return *choice.encoder;
}

}  // namespace rtmot::outputs
