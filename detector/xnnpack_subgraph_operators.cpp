// SubgraphBuilder's ONNX operators (xnnpack_subgraph_builder.hpp), fp32 and int8.
#include <algorithm>
#include <cmath>
#include <limits>

#include "detector/xnnpack_onnx_reading.hpp"
#include "detector/xnnpack_subgraph_builder.hpp"

namespace rtmot::detector::xnnpack {

namespace {

constexpr float kNoMin = -std::numeric_limits<float>::infinity();
constexpr float kNoMax = std::numeric_limits<float>::infinity();

}  // namespace

std::pair<float, float> SubgraphBuilder::clamp_bounds(const onnx::NodeProto& node) const {
  if (node.op_type() == "Relu") return {0.F, kNoMax};
  float low = kNoMin;
  float high = kNoMax;
  if (const auto* a = attribute(node, "min")) low = a->f();  // opset < 11
  if (const auto* a = attribute(node, "max")) high = a->f();
  for (int input = 1; input <= 2 && input < node.input_size(); ++input) {  // opset >= 11
    if (node.input(input).empty()) continue;
    const auto bound = floats(node, initializer(node, input));
    if (bound.size() != 1) throw error(node, "a bound must be a scalar");
    (input == 1 ? low : high) = bound[0];
  }
  if (std::isnan(low) || std::isnan(high) || low > high) throw error(node, "invalid bounds");
  return {low, high};
}

int SubgraphBuilder::fusable_activation(const onnx::NodeProto& conv) const {
  const std::string& out = conv.output(0);
  const auto reader = reader_.find(out);
  if (reader == reader_.end()) return -1;
  const onnx::NodeProto& candidate = graph_.node(reader->second);
  if ((candidate.op_type() != "Clip" && candidate.op_type() != "Relu") ||
      candidate.input(0) != out || consumers_.at(out) != 1 || external_ids_.count(out)) {
    return -1;
  }
  return reader->second;
}

void SubgraphBuilder::conv(const onnx::NodeProto& node, const onnx::NodeProto* activation) {
  const Value& input = xnn_value_of(node, 0);
  if (!input.nchw) throw error(node, "the input is not a 4-D feature map");
  const auto auto_pad = attribute(node, "auto_pad");
  if (auto_pad && auto_pad->s() != "NOTSET" && auto_pad->s() != "VALID") {
    throw error(node, "auto_pad " + auto_pad->s() + " is not supported (explicit pads are)");
  }
  const onnx::TensorProto& weight_tensor = initializer(node, 1);
  const std::vector<std::size_t> w(weight_tensor.dims().begin(), weight_tensor.dims().end());
  if (w.size() != 4) throw error(node, "only 2-D convolutions are supported");
  const auto weights = floats(node, weight_tensor);
  const std::size_t out_channels = w[0];
  const std::size_t group_in = w[1];
  const std::size_t kh = w[2];
  const std::size_t kw = w[3];
  const std::int64_t group_attribute = int_attribute(node, "group", 1);
  if (!declared_size_ok(group_attribute, 1)) {
    throw error(node, "group " + std::to_string(group_attribute) + " is outside 1.." +
                          std::to_string(kMaxDeclaredSize));
  }
  const auto groups = static_cast<std::size_t>(group_attribute);
  const std::size_t in_channels = input.shape[1];
  if (groups == 0 || group_in * groups != in_channels || out_channels % groups != 0) {
    throw error(node, "weights " + shape_text(w) + " do not fit " + std::to_string(in_channels) +
                          " input channels in " + std::to_string(groups) + " groups");
  }
  std::vector<float> bias(out_channels, 0.F);
  if (node.input_size() > 2 && !node.input(2).empty()) {
    bias = floats(node, initializer(node, 2));
    if (bias.size() != out_channels) throw error(node, "bias size does not match the weights");
  }
  const auto strides = ints_attribute(node, "strides", {1, 1});
  const auto dilations = ints_attribute(node, "dilations", {1, 1});
  const auto pads = ints_attribute(node, "pads", {0, 0, 0, 0});  // top, left, bottom, right
  const auto all_within = [](const std::vector<std::int64_t>& values, std::int64_t least) {
    return std::all_of(values.begin(), values.end(),
                       [least](std::int64_t v) { return declared_size_ok(v, least); });
  };
  if (strides.size() != 2 || dilations.size() != 2 || pads.size() != 4 || !all_within(strides, 1) ||
      !all_within(dilations, 1) || !all_within(pads, 0)) {
    throw error(node, "invalid strides, dilations or pads (each at most " +
                          std::to_string(kMaxDeclaredSize) + ")");
  }
  const auto extent = [](std::size_t size, std::int64_t pad_a, std::int64_t pad_b,
                         std::size_t kernel, std::int64_t dilation, std::int64_t stride) {
    const auto padded = static_cast<std::int64_t>(size) + pad_a + pad_b;
    const auto span = (static_cast<std::int64_t>(kernel) - 1) * dilation + 1;
    return padded < span ? std::int64_t{0} : (padded - span) / stride + 1;
  };
  const auto oh = extent(input.shape[2], pads[0], pads[2], kh, dilations[0], strides[0]);
  const auto ow = extent(input.shape[3], pads[1], pads[3], kw, dilations[1], strides[1]);
  if (oh < 1 || ow < 1) throw error(node, "the kernel is larger than its padded input");
  const auto [low, high] = activation ? clamp_bounds(*activation) : std::pair{kNoMin, kNoMax};
  const std::string& out_name = activation ? activation->output(0) : node.output(0);
  const std::vector<std::size_t> out_nhwc{batch_, static_cast<std::size_t>(oh),
                                          static_cast<std::size_t>(ow), out_channels};
  const auto u32 = [](auto v) { return static_cast<uint32_t>(v); };
  const bool depthwise = group_in == 1 && groups == in_channels && groups > 1;
  const std::vector<std::size_t> out_nchw{batch_, out_channels, static_cast<std::size_t>(oh),
                                          static_cast<std::size_t>(ow)};
  if (mode_.ranges) {
    const Value in = quantized(node.input(0), input);
    uint32_t output = XNN_INVALID_VALUE_ID;
    Value value = quantized_result(out_name, out_nchw, true, output);
    const auto [filter_id, bias_id] =
        quantized_weights(node, weights, bias, in.scale, depthwise, w);
    if (depthwise) {
      check(xnn_define_depthwise_convolution_2d(
                subgraph_, u32(pads[0]), u32(pads[3]), u32(pads[2]), u32(pads[1]), u32(kh), u32(kw),
                u32(strides[0]), u32(strides[1]), u32(dilations[0]), u32(dilations[1]),
                u32(out_channels / in_channels), in_channels, low, high, in.id, filter_id, bias_id,
                output, 0),
            "build node '" + node.name() + "' (int8)");
    } else {
      check(xnn_define_convolution_2d(
                subgraph_, u32(pads[0]), u32(pads[3]), u32(pads[2]), u32(pads[1]), u32(kh), u32(kw),
                u32(strides[0]), u32(strides[1]), u32(dilations[0]), u32(dilations[1]), u32(groups),
                group_in, out_channels / groups, low, high, in.id, filter_id, bias_id, output, 0),
            "build node '" + node.name() + "' (int8)");
    }
    flush_converts("node '" + node.name() + "'");
    values_[out_name] = value;
    return;
  }
  const uint32_t output = define_computed(out_name, out_nhwc);
  const uint32_t bias_id =
      define_static(node.input(1) + "#bias", {out_channels}, bias);  // keyed by the weights
  if (depthwise) {
    // ONNX [C*m, 1, KH, KW] -> XNNPACK [1, KH, KW, C*m].
    std::vector<float> filter(weights.size());
    for (std::size_t o = 0; o < out_channels; ++o) {
      for (std::size_t k = 0; k < kh * kw; ++k)
        filter[k * out_channels + o] = weights[o * kh * kw + k];
    }
    const uint32_t filter_id =
        define_static(node.input(1) + "#1hwo", {1, kh, kw, out_channels}, filter);
    check(xnn_define_depthwise_convolution_2d(subgraph_, u32(pads[0]), u32(pads[3]), u32(pads[2]),
                                              u32(pads[1]), u32(kh), u32(kw), u32(strides[0]),
                                              u32(strides[1]), u32(dilations[0]), u32(dilations[1]),
                                              u32(out_channels / in_channels), in_channels, low,
                                              high, input.id, filter_id, bias_id, output, 0),
          "build node '" + node.name() + "'");
  } else {
    // ONNX [O, I/g, KH, KW] -> XNNPACK [O, KH, KW, I/g].
    std::vector<float> filter(weights.size());
    for (std::size_t o = 0; o < out_channels; ++o) {
      for (std::size_t i = 0; i < group_in; ++i) {
        for (std::size_t k = 0; k < kh * kw; ++k) {
          filter[(o * kh * kw + k) * group_in + i] = weights[(o * group_in + i) * kh * kw + k];
        }
      }
    }
    const uint32_t filter_id =
        define_static(node.input(1) + "#ohwi", {out_channels, kh, kw, group_in}, filter);
    check(xnn_define_convolution_2d(
              subgraph_, u32(pads[0]), u32(pads[3]), u32(pads[2]), u32(pads[1]), u32(kh), u32(kw),
              u32(strides[0]), u32(strides[1]), u32(dilations[0]), u32(dilations[1]), u32(groups),
              group_in, out_channels / groups, low, high, input.id, filter_id, bias_id, output, 0),
          "build node '" + node.name() + "'");
  }
  Value value;
  value.id = output;
  value.shape = {batch_, out_channels, static_cast<std::size_t>(oh), static_cast<std::size_t>(ow)};
  value.nchw = true;
  values_[out_name] = value;
}

int SubgraphBuilder::scalar_operand(const onnx::NodeProto& node) const {
  for (int input = 0; input < std::min(node.input_size(), 2); ++input) {
    const auto found = initializers_.find(node.input(input));
    if (found == initializers_.end()) continue;
    std::size_t count = 1;
    for (const auto dim : found->second->dims())
      count *= static_cast<std::size_t>(std::max<std::int64_t>(dim, 0));
    if (count == 1) return input;
  }
  return -1;
}

void SubgraphBuilder::scalar_arithmetic(const onnx::NodeProto& node) {
  const int constant = scalar_operand(node);
  const Value& input = xnn_value_of(node, 1 - constant);
  if (input.qs8) {
    throw error(node,
                "the int8 engine runs arithmetic with a constant only on fp32 tensors (the "
                "model's input); use backend: xnnpack");
  }
  const std::vector<float> scalar = floats(node, initializer(node, constant));
  const auto dims = xnn_dims(input);
  const uint32_t scalar_id = define_static(node.input(constant) + "#scalar",
                                           std::vector<std::size_t>(dims.size(), 1), scalar);
  Value value = input;
  value.id = define_computed(node.output(0), dims);
  const uint32_t first = constant == 0 ? scalar_id : input.id;
  const uint32_t second = constant == 0 ? input.id : scalar_id;
  const std::string& op = node.op_type();
  const std::string what = "build node '" + node.name() + "'";
  if (op == "Add") {
    check(xnn_define_add2(subgraph_, kNoMin, kNoMax, first, second, value.id, 0), what);
  } else if (op == "Mul") {
    check(xnn_define_multiply2(subgraph_, kNoMin, kNoMax, first, second, value.id, 0), what);
  } else if (op == "Sub") {
    check(xnn_define_subtract(subgraph_, kNoMin, kNoMax, first, second, value.id, 0), what);
  } else {
    check(xnn_define_divide(subgraph_, kNoMin, kNoMax, first, second, value.id, 0), what);
  }
  values_[node.output(0)] = value;
}

void SubgraphBuilder::clamp(const onnx::NodeProto& node) {
  const auto [low, high] = clamp_bounds(node);
  if (mode_.ranges) {
    // A clamp keeps its input's quantization: it only cuts values off.
    const Value in = quantized(node.input(0), xnn_value_of(node, 0));
    Value value = in;
    value.id = define_quantized(node.output(0), xnn_dims(in), {in.scale, in.zero_point});
    check(xnn_define_clamp(subgraph_, low, high, in.id, value.id, 0),
          "build node '" + node.name() + "' (int8)");
    if (external_ids_.count(node.output(0))) {
      const uint32_t q = value.id;
      value.qs8 = false;
      value.id = define_computed(node.output(0), xnn_dims(in));
      check(xnn_define_convert(subgraph_, q, value.id, 0), "convert a clamp to fp32");
    }
    values_[node.output(0)] = value;
    return;
  }
  const Value& input = xnn_value_of(node, 0);
  Value value = input;
  value.id = define_computed(node.output(0), xnn_dims(input));
  check(xnn_define_clamp(subgraph_, low, high, input.id, value.id, 0),
        "build node '" + node.name() + "'");
  values_[node.output(0)] = value;
}

void SubgraphBuilder::add(const onnx::NodeProto& node) {
  const Value& a = xnn_value_of(node, 0);
  const Value& b = xnn_value_of(node, 1);
  if (a.shape != b.shape || a.nchw != b.nchw) {
    throw error(node, "adds " + shape_text(a.shape) + " and " + shape_text(b.shape) +
                          "; the xnnpack backend adds tensors of one shape");
  }
  if (mode_.ranges) {
    const Value qa = quantized(node.input(0), a);
    const Value qb = quantized(node.input(1), b);
    uint32_t output = XNN_INVALID_VALUE_ID;
    Value value = quantized_result(node.output(0), a.shape, a.nchw, output);
    check(xnn_define_add2(subgraph_, kNoMin, kNoMax, qa.id, qb.id, output, 0),
          "build node '" + node.name() + "' (int8)");
    flush_converts("node '" + node.name() + "'");
    values_[node.output(0)] = value;
    return;
  }
  Value value = a;
  value.id = define_computed(node.output(0), xnn_dims(a));
  check(xnn_define_add2(subgraph_, kNoMin, kNoMax, a.id, b.id, value.id, 0),
        "build node '" + node.name() + "'");
  values_[node.output(0)] = value;
}

void SubgraphBuilder::transpose(const onnx::NodeProto& node) {
  const Value& input = xnn_value_of(node, 0);
  const auto perm = ints_attribute(node, "perm", {});
  if (!input.nchw || perm != std::vector<std::int64_t>{0, 2, 3, 1}) {
    throw error(node,
                "only the NCHW -> NHWC transpose (perm 0,2,3,1) of a feature map is "
                "supported by the xnnpack backend");
  }
  Value value = input;
  value.shape = {input.shape[0], input.shape[2], input.shape[3], input.shape[1]};
  value.nchw = false;
  values_[node.output(0)] = value;
}

void SubgraphBuilder::reshape(const onnx::NodeProto& node) {
  const Value& input = value_of(node, 0);
  if (input.nchw || !input.pieces.empty()) {
    throw error(node,
                "reshapes an NCHW feature map or a concatenation; the xnnpack backend "
                "reshapes NHWC tensors only");
  }
  const auto wanted = int64s(node, initializer(node, 1));
  std::vector<std::size_t> shape(wanted.size(), 1);
  int infer = -1;
  std::size_t known = 1;
  for (std::size_t i = 0; i < wanted.size(); ++i) {
    if (wanted[i] == -1 && infer < 0) {
      infer = static_cast<int>(i);
      continue;
    }
    if (wanted[i] == 0 && i < input.shape.size()) {
      shape[i] = input.shape[i];
    } else if (wanted[i] > 0) {
      shape[i] = static_cast<std::size_t>(wanted[i]);
    } else {
      throw error(node, "invalid target shape");
    }
    known *= shape[i];
  }
  const std::size_t total = product(input.shape);
  if (infer >= 0) shape[static_cast<std::size_t>(infer)] = known ? total / known : 0;
  if (product(shape) != total || shape.empty() || shape[0] != batch_) {
    throw error(node, "cannot reshape " + shape_text(input.shape) + " to " + shape_text(shape) +
                          " image by image");
  }
  Value value = input;
  value.xnn_shape = value.xnn_shape && shape == input.shape;
  value.shape = shape;
  values_[node.output(0)] = value;
}

void SubgraphBuilder::concat(const onnx::NodeProto& node) {
  auto axis = int_attribute(node, "axis", 1);
  Value value;
  for (int i = 0; i < node.input_size(); ++i) {
    const Value& input = value_of(node, i);
    if (input.nchw || !input.pieces.empty() || !external_sizes_.count(input.id)) {
      throw error(node,
                  "the xnnpack backend concatenates only NHWC tensors that are graph "
                  "outputs' last computed values");
    }
    if (axis < 0) axis += static_cast<std::int64_t>(input.shape.size());
    if (axis != 1) throw error(node, "only axis 1 (anchors) is supported");
    if (i == 0) {
      value.shape = input.shape;
    } else {
      std::vector<std::size_t> a = value.shape;
      std::vector<std::size_t> b = input.shape;
      if (a.size() != b.size()) throw error(node, "inputs of different ranks");
      a[1] = b[1] = 0;
      if (a != b) throw error(node, "inputs differ outside the concatenated axis");
      value.shape[1] += input.shape[1];
    }
    value.pieces.push_back(input.id);
  }
  value.xnn_shape = false;
  values_[node.output(0)] = value;
}

}  // namespace rtmot::detector::xnnpack
