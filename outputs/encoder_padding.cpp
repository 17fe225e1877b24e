#include "outputs/encoder_padding.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>

namespace rtmot::outputs {

int min_encoder_side(VideoCodec codec) {
  return codec == VideoCodec::h265 ? 64 : 16;
}

EncoderPadding encoder_padding_of(VideoCodec codec, int width, int height) {
  const int min_side = min_encoder_side(codec);
  const auto fitted = [min_side](int side) { return std::max(min_side, side + (side & 1)); };
  return {fitted(width) - width, fitted(height) - height};
}

std::string encoder_padding(VideoCodec codec, int width, int height) {
  const EncoderPadding padding = encoder_padding_of(codec, width, height);
  if (padding.none()) return "";
  // videobox adds a border for negative values.
  return fmt::format("videobox right={} bottom={} ! ", -padding.right, -padding.bottom);
}

void set_encoder_padding(GstElement* videobox, VideoCodec codec, int width, int height) {
  const EncoderPadding padding = encoder_padding_of(codec, width, height);
  g_object_set(videobox, "right", -padding.right, "bottom", -padding.bottom, nullptr);
}

void warn_if_padded(const std::string& output, const VideoEncoder& encoder, int width, int height) {
  const EncoderPadding padding = encoder_padding_of(encoder.codec, width, height);
  if (padding.none()) return;
  spdlog::warn("{}: frames of {}x{} are padded with black to {}x{}, a size the {} encoder {} takes",
               output, width, height, width + padding.right, height + padding.bottom,
               codec_title(encoder.codec), encoder.element);
}

}  // namespace rtmot::outputs
