#pragma once
// The int8 engine's arithmetic (backend xnnpack-int8, docs/cpu-detector.md): activations
// quantized per tensor from their calibrated ranges (activation_ranges.hpp), weights per output
// channel, and the store of the quantized weights the runtimes point into. Internal to detector/.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "detector/activation_ranges.hpp"

namespace rtmot::detector::xnnpack {

/// The int8 engine's weights in XNNPACK's formats, made once per model and shared by every
/// runtime (XNNPACK keeps pointers to them and to the per-channel scales).
struct QuantizedWeights {
  std::map<std::string, std::vector<std::int8_t>> filters;
  std::map<std::string, std::vector<std::int32_t>> biases;
  std::map<std::string, std::vector<float>> scales;
};

struct Quantization {
  float scale;
  std::int32_t zero_point;
};

/// Asymmetric int8 over the calibrated range widened to hold 0 (zero padding must be exact).
Quantization activation_quantization(const ActivationRange& range);

/// Symmetric per-channel int8 weights: channel c's `per_channel` values are at(c, k), each stored
/// at out[where(c, k)] (XNNPACK's layout). Returns the channels' scales.
template <typename Weight, typename Slot>
std::vector<float> quantize_per_channel(std::size_t channels, std::size_t per_channel, Weight at,
                                        Slot where, std::vector<std::int8_t>& out) {
  std::vector<float> scales(channels, 1.F);
  out.assign(channels * per_channel, 0);
  for (std::size_t c = 0; c < channels; ++c) {
    float largest = 0.F;
    for (std::size_t k = 0; k < per_channel; ++k) largest = std::max(largest, std::fabs(at(c, k)));
    scales[c] = largest > 0.F ? largest / 127.F : 1.F;
    for (std::size_t k = 0; k < per_channel; ++k) {
      const long q = std::lround(at(c, k) / scales[c]);
      out[where(c, k)] = static_cast<std::int8_t>(std::clamp(q, -127L, 127L));
    }
  }
  return scales;
}

}  // namespace rtmot::detector::xnnpack
