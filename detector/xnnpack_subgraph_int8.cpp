// SubgraphBuilder's int8 engine (xnnpack_subgraph_builder.hpp): the quantization of each
// tensor from its calibrated range, the converts at the fp32 edges, a convolution's int8
// weights.
#include <algorithm>
#include <cmath>

#include "detector/xnnpack_subgraph_builder.hpp"

namespace rtmot::detector::xnnpack {

Quantization SubgraphBuilder::quantization_of(const std::string& tensor) const {
  const auto found = mode_.ranges->tensors.find(tensor);
  if (found == mode_.ranges->tensors.end()) {
    throw InputError(mode_.ranges_path->string(), 0, "range",
                     "no range for the model's tensor '" + tensor +
                         "' (made for another model? calibrate with scripts/calibrate_int8.sh)",
                     ExitCode::bad_model);
  }
  return activation_quantization(found->second);
}

Value SubgraphBuilder::quantized(const std::string& tensor, const Value& value) {
  if (value.qs8) return value;
  const auto done = converted_.find(tensor);
  if (done != converted_.end()) return done->second;
  const Quantization q = quantization_of(tensor);
  Value result = value;
  result.qs8 = true;
  result.scale = q.scale;
  result.zero_point = q.zero_point;
  result.id = define_quantized(tensor, xnn_dims(value), q);
  check(xnn_define_convert(subgraph_, value.id, result.id, 0), "convert '" + tensor + "' to int8");
  converted_[tensor] = result;
  return result;
}

uint32_t SubgraphBuilder::define_quantized(const std::string& name,
                                           const std::vector<std::size_t>& xnn_dims,
                                           Quantization q) {
  check_size(name, xnn_dims);
  uint32_t id = XNN_INVALID_VALUE_ID;
  check(xnn_define_quantized_tensor_value(subgraph_, xnn_datatype_qint8, q.zero_point, q.scale,
                                          xnn_dims.size(), xnn_dims.data(), nullptr,
                                          XNN_INVALID_VALUE_ID, 0, &id),
        "define the int8 tensor '" + name + "'");
  return id;
}

Value SubgraphBuilder::quantized_result(const std::string& name,
                                        const std::vector<std::size_t>& onnx_shape, bool nchw,
                                        uint32_t& into) {
  Value value;
  value.shape = onnx_shape;
  value.nchw = nchw;
  const auto dims = xnn_dims(value);
  const Quantization q = quantization_of(name);
  into = define_quantized(name, dims, q);
  if (external_ids_.count(name)) {
    value.id = define_computed(name, dims);
    pending_converts_.emplace_back(into, value.id);
    return value;
  }
  value.id = into;
  value.qs8 = true;
  value.scale = q.scale;
  value.zero_point = q.zero_point;
  return value;
}

void SubgraphBuilder::flush_converts(const std::string& what) {
  for (const auto& [from, to] : pending_converts_) {
    check(xnn_define_convert(subgraph_, from, to, 0), "convert " + what + " to fp32");
  }
  pending_converts_.clear();
}

std::pair<uint32_t, uint32_t> SubgraphBuilder::quantized_weights(
    const onnx::NodeProto& node, const std::vector<float>& weights, const std::vector<float>& bias,
    float input_scale, bool depthwise, const std::vector<std::size_t>& w) {
  const std::size_t out_channels = w[0];
  const std::size_t group_in = w[1];
  const std::size_t taps = w[2] * w[3];
  QuantizedWeights& store = *mode_.quantized;
  const std::string key = node.input(1);
  auto& filter = store.filters[key];
  auto& scales = store.scales[key];
  if (filter.empty()) {
    // ONNX [O, I/g, KH, KW]: channel o's values are contiguous; XNNPACK's depthwise filter is
    // [1, KH, KW, O], the others [O, KH, KW, I/g].
    const auto weight = [&](std::size_t o, std::size_t k) {
      return weights[o * taps * group_in + k];
    };
    const auto slot = [&](std::size_t o, std::size_t k) {
      if (depthwise) return k * out_channels + o;
      const std::size_t i = k / taps;
      return (o * taps + k % taps) * group_in + i;
    };
    scales = quantize_per_channel(out_channels, taps * group_in, weight, slot, filter);
  }
  // The bias's scale depends on the input's, one calibrated value per tensor: keyed by both.
  auto& bias_scales = store.scales[key + "#bias@" + node.input(0)];
  auto& bias_q = store.biases[key + "#bias@" + node.input(0)];
  if (bias_q.empty()) {
    bias_scales.resize(out_channels);
    bias_q.resize(out_channels);
    for (std::size_t o = 0; o < out_channels; ++o) {
      bias_scales[o] = input_scale * scales[o];
      const double q = std::round(static_cast<double>(bias[o]) / bias_scales[o]);
      bias_q[o] = static_cast<std::int32_t>(std::clamp(q, -2147483647.0, 2147483647.0));
    }
  }
  const std::vector<std::size_t> filter_dims =
      depthwise ? std::vector<std::size_t>{1, w[2], w[3], out_channels}
                : std::vector<std::size_t>{out_channels, w[2], w[3], group_in};
  uint32_t filter_id = XNN_INVALID_VALUE_ID;
  check(xnn_define_channelwise_quantized_tensor_value(
            subgraph_, xnn_datatype_qcint8, scales.data(), filter_dims.size(), depthwise ? 3 : 0,
            filter_dims.data(), filter.data(), XNN_INVALID_VALUE_ID, 0, &filter_id),
        "define the int8 weights '" + key + "'");
  const std::size_t bias_dims[] = {out_channels};
  uint32_t bias_id = XNN_INVALID_VALUE_ID;
  check(xnn_define_channelwise_quantized_tensor_value(
            subgraph_, xnn_datatype_qcint32, bias_scales.data(), 1, 0, bias_dims, bias_q.data(),
            XNN_INVALID_VALUE_ID, 0, &bias_id),
        "define the int32 bias of '" + key + "'");
  return {filter_id, bias_id};
}

}  // namespace rtmot::detector::xnnpack
