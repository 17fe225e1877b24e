#include "outputs/encoder_padding.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>

namespace rtmot::outputs {
namespace {

constexpr int kMinEncoderSide = 16;

}  // namespace

EncoderPadding encoder_padding_of(int width, int height) {
  const auto fitted = [](int side) { return std::max(kMinEncoderSide, side + (side & 1)); };
  return {fitted(width) - width, fitted(height) - height};
}

std::string encoder_padding(int width, int height) {
  const EncoderPadding padding = encoder_padding_of(width, height);
  if (padding.none()) return "";
  // videobox adds a border for negative values.
  return fmt::format("videobox right={} bottom={} ! ", -padding.right, -padding.bottom);
}

void set_encoder_padding(GstElement* videobox, int width, int height) {
  const EncoderPadding padding = encoder_padding_of(width, height);
  g_object_set(videobox, "right", -padding.right, "bottom", -padding.bottom, nullptr);
}

void warn_if_padded(const std::string& output, int width, int height) {
  if (encoder_padding_of(width, height).none()) return;
  spdlog::warn("{}: frames of {}x{} are padded with black to a size the H.264 encoder takes",
               output, width, height);
}

}  // namespace rtmot::outputs
