#include "detector/xnnpack_quantization.hpp"

namespace rtmot::detector::xnnpack {

Quantization activation_quantization(const ActivationRange& range) {
  const float low = std::min(range.min, 0.F);
  const float high = std::max(range.max, 0.F);
  // XNNPACK wants a normal positive scale; a tensor that was always 0 gets any.
  const float scale = std::max((high - low) / 255.F, 1e-8F);
  const long zero_point = std::lround(-128.F - low / scale);
  return {scale, static_cast<std::int32_t>(std::clamp(zero_point, -128L, 127L))};
}

}  // namespace rtmot::detector::xnnpack
