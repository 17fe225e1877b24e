#include "detector/xnnpack_network.hpp"

#include <onnx/onnx_pb.h>
#include <pthreadpool.h>
#include <xnnpack.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <opencv2/core/utility.hpp>
#include <set>
#include <sstream>
#include <vector>

#include "common/input_error.hpp"
#include "detector/model_checksum.hpp"
#include "detector/model_files.hpp"
#include "detector/pool_governor.hpp"
#include "detector/xnnpack_decoding_tail.hpp"
#include "detector/xnnpack_onnx_reading.hpp"
#include "detector/xnnpack_quantization.hpp"

namespace rtmot::detector {

bool xnnpack_built() {
  return true;
}

bool xnnpack_runs_here() {
  return xnn_initialize(nullptr) == xnn_status_success;
}

const char* xnnpack_supported_operators() {
  return "Conv (any group count, dilation, explicit pads), Clip, Relu, Add (same shapes), "
         "Add, Mul, Sub, Div by a scalar constant, Transpose (NCHW -> NHWC), Reshape, Concat "
         "(axis 1), Identity; after them, on the host, a decoding tail of Slice, Mul, Add, Sub, "
         "Div, Exp, Sigmoid, Softmax, Concat, Reshape, Unsqueeze, Squeeze, Flatten, Identity, "
         "Constant";
}

namespace {

using xnnpack::activation_quantization;
using xnnpack::attribute;
using xnnpack::declared_size_ok;
using xnnpack::int_attribute;
using xnnpack::ints_attribute;
using xnnpack::kMaxDeclaredSize;
using xnnpack::kMaxTensorFloatsPerImage;
using xnnpack::product;
using xnnpack::Quantization;
using xnnpack::quantize_per_channel;
using xnnpack::QuantizedWeights;
using xnnpack::shape_text;

constexpr uint32_t kInputExternalId = 0;
constexpr float kNoMin = -std::numeric_limits<float>::infinity();
constexpr float kNoMax = std::numeric_limits<float>::infinity();

struct SubgraphDeleter {
  void operator()(xnn_subgraph_t subgraph) const { xnn_delete_subgraph(subgraph); }
};
struct RuntimeDeleter {
  void operator()(xnn_runtime_t runtime) const { xnn_delete_runtime(runtime); }
};
struct PoolDeleter {
  void operator()(pthreadpool_t pool) const { pthreadpool_destroy(pool); }
};
using SubgraphPtr = std::unique_ptr<xnn_subgraph, SubgraphDeleter>;
using RuntimePtr = std::unique_ptr<xnn_runtime, RuntimeDeleter>;
using PoolPtr = std::unique_ptr<pthreadpool, PoolDeleter>;

/// A tensor as the builder tracks it.
struct Value {
  uint32_t id{XNN_INVALID_VALUE_ID};
  std::vector<std::size_t> shape;  // as ONNX sees it
  /// A 4-D feature map that ONNX sees as NCHW and XNNPACK holds as NHWC.
  bool nchw{false};
  /// False after a Reshape: XNNPACK still has the old shape (a reshape of contiguous data moves
  /// nothing, so none is run); only host-side consumers (Concat, the graph's outputs) may read it.
  bool xnn_shape{true};
  /// Set on a Concat's result: the external outputs it joins, in order (host side).
  std::vector<uint32_t> pieces;
  /// Signed 8-bit (the int8 engine): real = scale * (q - zero_point).
  bool qs8{false};
  float scale{1.F};
  std::int32_t zero_point{0};
};

/// What the builder does besides fp32: quantize (ranges set) or record ranges (probes set).
struct BuildMode {
  const ActivationRanges* ranges{nullptr};
  const std::filesystem::path* ranges_path{nullptr};
  QuantizedWeights* quantized{nullptr};
  std::map<std::string, uint32_t>* probes{nullptr};  // tensor -> its external id
};

/// Builds one subgraph (one batch size) from the parsed model. The converted weights live in
/// `weights`, shared by every subgraph built from the model and alive as long as the runtimes.
class SubgraphBuilder {
 public:
  SubgraphBuilder(const std::filesystem::path& path, const onnx::GraphProto& graph,
                  const TailSplit& split, std::map<std::string, std::vector<float>>& weights,
                  const std::map<std::string, uint32_t>& external_ids, std::size_t batch,
                  std::size_t input_size, BuildMode mode)
      : path_(path),
        graph_(graph),
        split_(split),
        weights_(weights),
        external_ids_(external_ids),
        batch_(batch),
        input_size_(input_size),
        mode_(mode) {
    for (const auto& tensor : graph_.initializer()) initializers_[tensor.name()] = &tensor;
    // Exporters write constants as Constant nodes too (torch.onnx without constant folding): the
    // same tensors (the node itself is computed on the host, once: xnnpack_decoding_tail.hpp).
    for (const auto& node : graph_.node()) {
      const auto* value = node.op_type() == "Constant" && node.output_size() == 1
                              ? attribute(node, "value")
                              : nullptr;
      if (value) initializers_[node.output(0)] = &value->t();
    }
    for (int index = 0; index < graph_.node_size(); ++index) {
      for (const auto& input : graph_.node(index).input()) {
        ++consumers_[input];
        reader_[input] = index;
      }
    }
    for (const auto& output : graph_.output()) ++consumers_[output.name()];
  }

  /// The subgraph of the network's nodes (the split's others run on the host); `outputs` gets
  /// the value of each tensor the host reads (pieces set).
  SubgraphPtr build(std::map<std::string, Value>& outputs,
                    std::map<uint32_t, std::size_t>& external_sizes) {
    xnn_subgraph_t raw = nullptr;
    // Recording ranges makes every computed tensor an external output: at most one a node.
    const auto externals = static_cast<uint32_t>(external_ids_.size()) + 1 +
                           (mode_.probes ? static_cast<uint32_t>(graph_.node_size()) : 0U);
    next_probe_id_ = static_cast<uint32_t>(external_ids_.size()) + 1;
    check(xnn_create_subgraph(externals, 0, &raw), "create the subgraph");
    SubgraphPtr subgraph(raw);
    subgraph_ = raw;
    define_input();
    const int count = graph_.node_size();
    std::vector<bool> fused(static_cast<std::size_t>(count), false);
    for (int index = 0; index < count; ++index) {
      if (fused[static_cast<std::size_t>(index)]) continue;
      if (split_.on_host[static_cast<std::size_t>(index)]) continue;
      const onnx::NodeProto& node = graph_.node(index);
      const std::string& op = node.op_type();
      if ((op == "Add" || op == "Mul" || op == "Sub" || op == "Div") && scalar_operand(node) >= 0) {
        scalar_arithmetic(node);
      } else if (op == "Conv") {
        const int activation = fusable_activation(node);
        if (activation >= 0) fused[static_cast<std::size_t>(activation)] = true;
        conv(node, activation >= 0 ? &graph_.node(activation) : nullptr);
      } else if (op == "Clip" || op == "Relu") {
        clamp(node);
      } else if (op == "Add") {
        add(node);
      } else if (op == "Transpose") {
        transpose(node);
      } else if (op == "Reshape") {
        reshape(node);
      } else if (op == "Concat") {
        concat(node);
      } else if (op == "Identity") {
        values_[node.output(0)] = value_of(node, 0);
      } else {
        throw error(node, "operator '" + op +
                              "' is not supported by the xnnpack backend (it builds " +
                              std::string(xnnpack_supported_operators()) + "): use backend: cpu");
      }
    }
    for (const std::string& name : split_.boundary) {
      const auto found = values_.find(name);
      if (found == values_.end()) {
        throw model_error("the tensor '" + name + "' is computed by no node");
      }
      Value value = found->second;
      if (value.nchw) {
        throw model_error("the feature map '" + name +
                          "' is read after the network in NCHW order; XNNPACK holds it as NHWC");
      }
      if (value.pieces.empty()) value.pieces = {value.id};
      if (!external_sizes_.count(value.pieces.front())) {
        throw model_error("the tensor '" + name + "' is not computed here");
      }
      outputs[name] = value;
    }
    external_sizes = external_sizes_;
    return subgraph;
  }

 private:
  InputError model_error(const std::string& problem) const {
    return InputError(path_.string(), 0, "", problem, ExitCode::bad_model);
  }
  InputError error(const onnx::NodeProto& node, const std::string& problem) const {
    return model_error("node '" + node.name() + "' (" + node.op_type() + "): " + problem);
  }
  void check(xnn_status status, const std::string& what) const {
    if (status != xnn_status_success) {
      throw model_error("XNNPACK cannot " + what + " (status " +
                        std::to_string(static_cast<int>(status)) + ")");
    }
  }

  void define_input() {
    const onnx::ValueInfoProto* input = nullptr;
    for (const auto& candidate : graph_.input()) {
      if (!initializers_.count(candidate.name())) {
        if (input) throw model_error("the model has more than one input; the SSD takes one image");
        input = &candidate;
      }
    }
    if (!input) throw model_error("the model has no input");
    const auto& dims = input->type().tensor_type().shape().dim();
    const std::size_t want[] = {batch_, 3, input_size_, input_size_};
    std::string seen;
    bool ok = dims.size() == 4;
    for (int i = 0; i < dims.size(); ++i) {
      seen += (i ? "x" : "") +
              (dims[i].has_dim_value() ? std::to_string(dims[i].dim_value()) : dims[i].dim_param());
      if (ok && dims[i].has_dim_value() &&
          static_cast<std::size_t>(dims[i].dim_value()) != want[i]) {
        ok = false;
      }
    }
    if (!ok) {
      throw model_error("the model's input '" + input->name() + "' is " + seen +
                        "; the detector feeds " + std::to_string(batch_) + "x3x" +
                        std::to_string(input_size_) + "x" + std::to_string(input_size_) +
                        (batch_ > 1 ? " (a batch needs a batch dimension: run "
                                      "scripts/fetch_model.sh again)"
                                    : ""));
    }
    const std::vector<std::size_t> nhwc{batch_, input_size_, input_size_, 3};
    Value value;
    check(xnn_define_tensor_value(subgraph_, xnn_datatype_fp32, nhwc.size(), nhwc.data(), nullptr,
                                  kInputExternalId, XNN_VALUE_FLAG_EXTERNAL_INPUT, &value.id),
          "define the input");
    value.shape = {batch_, 3, input_size_, input_size_};
    value.nchw = true;
    values_[input->name()] = value;
    if (mode_.probes) (*mode_.probes)[input->name()] = kInputExternalId;
  }

  // --- the int8 engine ---

  Quantization quantization_of(const std::string& tensor) const {
    const auto found = mode_.ranges->tensors.find(tensor);
    if (found == mode_.ranges->tensors.end()) {
      throw InputError(mode_.ranges_path->string(), 0, "range",
                       "no range for the model's tensor '" + tensor +
                           "' (made for another model? calibrate with scripts/calibrate_int8.sh)",
                       ExitCode::bad_model);
    }
    return activation_quantization(found->second);
  }

  /// The tensor as int8: itself, or (the fp32 input, an fp32 graph output read again) converted
  /// once per subgraph.
  Value quantized(const std::string& tensor, const Value& value) {
    if (value.qs8) return value;
    const auto done = converted_.find(tensor);
    if (done != converted_.end()) return done->second;
    const Quantization q = quantization_of(tensor);
    Value result = value;
    result.qs8 = true;
    result.scale = q.scale;
    result.zero_point = q.zero_point;
    result.id = define_quantized(tensor, xnn_dims(value), q);
    check(xnn_define_convert(subgraph_, value.id, result.id, 0),
          "convert '" + tensor + "' to int8");
    converted_[tensor] = result;
    return result;
  }

  uint32_t define_quantized(const std::string& name, const std::vector<std::size_t>& xnn_dims,
                            Quantization q) {
    check_size(name, xnn_dims);
    uint32_t id = XNN_INVALID_VALUE_ID;
    check(xnn_define_quantized_tensor_value(subgraph_, xnn_datatype_qint8, q.zero_point, q.scale,
                                            xnn_dims.size(), xnn_dims.data(), nullptr,
                                            XNN_INVALID_VALUE_ID, 0, &id),
          "define the int8 tensor '" + name + "'");
    return id;
  }

  /// An int8 node's result `name`: its int8 tensor (defined here, into `into`), and the value the
  /// graph reads, which is fp32 (converted) where the tensor is an output the host reads.
  Value quantized_result(const std::string& name, const std::vector<std::size_t>& onnx_shape,
                         bool nchw, uint32_t& into) {
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

  /// The converts to fp32 outputs, defined after their producer (XNNPACK runs nodes in order).
  void flush_converts(const std::string& what) {
    for (const auto& [from, to] : pending_converts_) {
      check(xnn_define_convert(subgraph_, from, to, 0), "convert " + what + " to fp32");
    }
    pending_converts_.clear();
  }

  const Value& value_of(const onnx::NodeProto& node, int input) const {
    if (input >= node.input_size())
      throw error(node, "input " + std::to_string(input) + " missing");
    const auto found = values_.find(node.input(input));
    if (found == values_.end()) {
      throw error(node, "input '" + node.input(input) +
                            "' is not computed by an earlier node (constant activations are not "
                            "supported by the xnnpack backend)");
    }
    return found->second;
  }

  const Value& xnn_value_of(const onnx::NodeProto& node, int input) const {
    const Value& value = value_of(node, input);
    if (!value.xnn_shape || !value.pieces.empty()) {
      throw error(node,
                  "reads a reshaped or concatenated tensor; the xnnpack backend joins those "
                  "only at the graph's outputs");
    }
    return value;
  }

  const onnx::TensorProto& initializer(const onnx::NodeProto& node, int input) const {
    if (input >= node.input_size())
      throw error(node, "input " + std::to_string(input) + " missing");
    const auto found = initializers_.find(node.input(input));
    if (found == initializers_.end()) {
      throw error(node, "input '" + node.input(input) + "' must be a constant (initializer)");
    }
    return *found->second;
  }

  std::vector<float> floats(const onnx::NodeProto& node, const onnx::TensorProto& tensor) const {
    if (tensor.data_type() != onnx::TensorProto::FLOAT) {
      throw error(node, "weight tensor '" + tensor.name() + "' is not float32");
    }
    std::vector<float> data;
    if (!tensor.raw_data().empty()) {
      data.resize(tensor.raw_data().size() / sizeof(float));
      std::memcpy(data.data(), tensor.raw_data().data(), data.size() * sizeof(float));
    } else {
      data.assign(tensor.float_data().begin(), tensor.float_data().end());
    }
    for (const std::int64_t dim : tensor.dims()) {
      if (!declared_size_ok(dim, 0)) {
        throw error(node, "weight tensor '" + tensor.name() + "' declares a dimension of " +
                              std::to_string(dim) + " (at most " +
                              std::to_string(kMaxDeclaredSize) + ")");
      }
    }
    std::vector<std::size_t> dims(tensor.dims().begin(), tensor.dims().end());
    if (data.size() != product(dims)) {
      throw error(node, "weight tensor '" + tensor.name() + "' holds " +
                            std::to_string(data.size()) + " values for shape " + shape_text(dims));
    }
    // NaN or infinite weights (a damaged or badly converted model) would make every score NaN,
    // and NaN compares false with the threshold: the detector would silently find nothing.
    if (!std::all_of(data.begin(), data.end(), [](float v) { return std::isfinite(v); })) {
      throw error(node, "weight tensor '" + tensor.name() +
                            "' holds NaN or infinite values (damaged model? run "
                            "scripts/fetch_model.sh again)");
    }
    return data;
  }

  std::vector<std::int64_t> int64s(const onnx::NodeProto& node,
                                   const onnx::TensorProto& tensor) const {
    if (tensor.data_type() != onnx::TensorProto::INT64) {
      throw error(node, "tensor '" + tensor.name() + "' is not int64");
    }
    std::vector<std::int64_t> data;
    if (!tensor.raw_data().empty()) {
      data.resize(tensor.raw_data().size() / sizeof(std::int64_t));
      std::memcpy(data.data(), tensor.raw_data().data(), data.size() * sizeof(std::int64_t));
    } else {
      data.assign(tensor.int64_data().begin(), tensor.int64_data().end());
    }
    return data;
  }

  /// A static tensor on converted weights, made once per model and shared by every batch size.
  uint32_t define_static(const std::string& key, const std::vector<std::size_t>& dims,
                         const std::vector<float>& data) {
    auto& stored = weights_[key];
    if (stored.empty()) stored = data;
    uint32_t id = XNN_INVALID_VALUE_ID;
    check(xnn_define_tensor_value(subgraph_, xnn_datatype_fp32, dims.size(), dims.data(),
                                  stored.data(), XNN_INVALID_VALUE_ID, 0, &id),
          "define the weights '" + key + "'");
    return id;
  }

  /// Every tensor the builder defines is bounded (fp32 or int8).
  void check_size(const std::string& name, const std::vector<std::size_t>& xnn_dims) const {
    if (xnn_dims.empty() || product(xnn_dims, 1) > kMaxTensorFloatsPerImage) {
      throw model_error("the tensor '" + name + "' would be " + shape_text(xnn_dims) +
                        " floats; at most " + std::to_string(kMaxTensorFloatsPerImage) +
                        " an image (damaged model? run scripts/fetch_model.sh again)");
    }
  }

  /// A computed tensor: an external output when it is (a piece of) a graph output, or recorded.
  uint32_t define_computed(const std::string& name, const std::vector<std::size_t>& xnn_dims) {
    check_size(name, xnn_dims);
    uint32_t external = XNN_INVALID_VALUE_ID;
    uint32_t flags = 0;
    const auto found = external_ids_.find(name);
    if (found != external_ids_.end()) {
      external = found->second;
      if (mode_.probes) (*mode_.probes)[name] = external;
    } else if (mode_.probes) {
      external = next_probe_id_++;
      (*mode_.probes)[name] = external;
    }
    if (external != XNN_INVALID_VALUE_ID) {
      flags = XNN_VALUE_FLAG_EXTERNAL_OUTPUT;
      external_sizes_[external] = product(xnn_dims, 1);
    }
    uint32_t id = XNN_INVALID_VALUE_ID;
    check(xnn_define_tensor_value(subgraph_, xnn_datatype_fp32, xnn_dims.size(), xnn_dims.data(),
                                  nullptr, external, flags, &id),
          "define the tensor '" + name + "'");
    return id;
  }

  /// The bounds of a Clip or Relu node.
  std::pair<float, float> clamp_bounds(const onnx::NodeProto& node) const {
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

  /// The Clip/Relu right after a Conv that is its output's only reader: XNNPACK clamps in the
  /// convolution's own output loop, saving a pass over the feature map.
  /// Its node index, or -1.
  int fusable_activation(const onnx::NodeProto& conv) const {
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

  void conv(const onnx::NodeProto& node, const onnx::NodeProto* activation) {
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
    if (strides.size() != 2 || dilations.size() != 2 || pads.size() != 4 ||
        !all_within(strides, 1) || !all_within(dilations, 1) || !all_within(pads, 0)) {
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
                  subgraph_, u32(pads[0]), u32(pads[3]), u32(pads[2]), u32(pads[1]), u32(kh),
                  u32(kw), u32(strides[0]), u32(strides[1]), u32(dilations[0]), u32(dilations[1]),
                  u32(out_channels / in_channels), in_channels, low, high, in.id, filter_id,
                  bias_id, output, 0),
              "build node '" + node.name() + "' (int8)");
      } else {
        check(xnn_define_convolution_2d(subgraph_, u32(pads[0]), u32(pads[3]), u32(pads[2]),
                                        u32(pads[1]), u32(kh), u32(kw), u32(strides[0]),
                                        u32(strides[1]), u32(dilations[0]), u32(dilations[1]),
                                        u32(groups), group_in, out_channels / groups, low, high,
                                        in.id, filter_id, bias_id, output, 0),
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
      check(xnn_define_depthwise_convolution_2d(
                subgraph_, u32(pads[0]), u32(pads[3]), u32(pads[2]), u32(pads[1]), u32(kh), u32(kw),
                u32(strides[0]), u32(strides[1]), u32(dilations[0]), u32(dilations[1]),
                u32(out_channels / in_channels), in_channels, low, high, input.id, filter_id,
                bias_id, output, 0),
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
      check(xnn_define_convolution_2d(subgraph_, u32(pads[0]), u32(pads[3]), u32(pads[2]),
                                      u32(pads[1]), u32(kh), u32(kw), u32(strides[0]),
                                      u32(strides[1]), u32(dilations[0]), u32(dilations[1]),
                                      u32(groups), group_in, out_channels / groups, low, high,
                                      input.id, filter_id, bias_id, output, 0),
            "build node '" + node.name() + "'");
    }
    Value value;
    value.id = output;
    value.shape = {batch_, out_channels, static_cast<std::size_t>(oh),
                   static_cast<std::size_t>(ow)};
    value.nchw = true;
    values_[out_name] = value;
  }

  /// A convolution's weights for the int8 engine, in XNNPACK's layouts (as the fp32 ones below):
  /// int8 per output channel, and the bias as int32 at scale input_scale * channel_scale.
  std::pair<uint32_t, uint32_t> quantized_weights(const onnx::NodeProto& node,
                                                  const std::vector<float>& weights,
                                                  const std::vector<float>& bias, float input_scale,
                                                  bool depthwise,
                                                  const std::vector<std::size_t>& w) {
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

  /// The input (0 or 1) of a binary node that is a one-value initializer, or -1.
  int scalar_operand(const onnx::NodeProto& node) const {
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

  /// A tensor and a scalar constant (a model's own input normalisation, as the fixture of
  /// pytorch-ssd's interface has), broadcast by XNNPACK. fp32 in both engines: in the int8 one
  /// such a node may only read an fp32 tensor (the input), and the convolution after it converts.
  void scalar_arithmetic(const onnx::NodeProto& node) {
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

  void clamp(const onnx::NodeProto& node) {
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

  void add(const onnx::NodeProto& node) {
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

  // NCHW -> NHWC is what XNNPACK holds already: nothing to run.
  void transpose(const onnx::NodeProto& node) {
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

  void reshape(const onnx::NodeProto& node) {
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

  // Joined on the host (see XnnpackNetwork::run): each input is an external output. Axis 1 of
  // [N, ...] keeps each image's rows of one input contiguous, so the join is a copy per image.
  void concat(const onnx::NodeProto& node) {
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

  std::vector<std::size_t> xnn_dims(const Value& value) const {
    if (!value.nchw) return value.shape;
    return {value.shape[0], value.shape[2], value.shape[3], value.shape[1]};
  }

  const std::filesystem::path& path_;
  const onnx::GraphProto& graph_;
  const TailSplit& split_;
  std::map<std::string, std::vector<float>>& weights_;
  const std::map<std::string, uint32_t>& external_ids_;
  std::size_t batch_;
  std::size_t input_size_;
  BuildMode mode_;
  uint32_t next_probe_id_{0};
  std::map<std::string, Value> converted_;  // int8 copies of fp32 tensors, by tensor name
  std::vector<std::pair<uint32_t, uint32_t>> pending_converts_;
  std::map<std::string, const onnx::TensorProto*> initializers_;
  std::map<std::string, int> consumers_;
  std::map<std::string, int> reader_;  // a node reading the tensor (the only one where it matters)
  std::map<std::string, Value> values_;
  std::map<uint32_t, std::size_t> external_sizes_;
  xnn_subgraph_t subgraph_{nullptr};
};

/// The tensors that must be XNNPACK external outputs: what the tensors the host reads come from
/// once the moves that run nothing here (Identity, Reshape, Transpose, Concat) are looked through.
std::map<std::string, uint32_t> external_outputs(const onnx::GraphProto& graph,
                                                 const std::vector<std::string>& read) {
  std::map<std::string, const onnx::NodeProto*> producer;
  for (const auto& node : graph.node()) {
    for (const auto& output : node.output()) producer[output] = &node;
  }
  std::map<std::string, uint32_t> ids;
  std::vector<std::string> pending(read.begin(), read.end());
  while (!pending.empty()) {
    const std::string name = pending.back();
    pending.pop_back();
    const auto found = producer.find(name);
    if (found == producer.end()) continue;  // reported by the builder
    const onnx::NodeProto& node = *found->second;
    const std::string& op = node.op_type();
    if (op == "Concat") {
      for (const auto& input : node.input()) pending.push_back(input);
    } else if (op == "Identity" || op == "Reshape" || op == "Transpose") {
      pending.push_back(node.input(0));
    } else if (!ids.count(name)) {
      const auto id = static_cast<uint32_t>(ids.size()) + 1;  // 0 is the input
      ids[name] = id;
    }
  }
  return ids;
}

/// An external output's buffer and where its rows go in the joined output.
struct Piece {
  uint32_t id;
  std::size_t per_image;  // floats per image
  std::vector<float> data;
};

/// A tensor the host reads: its pieces joined image by image.
struct JoinedOutput {
  std::string name;
  std::vector<std::size_t> shape;  // ONNX's, for one image (batch 1)
  std::vector<std::size_t> piece_indices;
  std::size_t per_image{0};
  std::size_t width{0};  // the last dimension
  std::vector<float> data;
};

}  // namespace

struct XnnpackNetwork::Impl {
  XnnpackNetworkConfig config;
  onnx::ModelProto model;
  std::map<std::string, std::vector<float>> weights;  // outlive the runtimes (declared first)
  QuantizedWeights quantized_weights;
  ActivationRanges ranges;  // the int8 engine's calibration (empty: fp32)
  std::string model_sha256;
  // Recording ranges: each recorded tensor's external id, its buffer and what it held so far.
  std::map<std::string, uint32_t> probes;
  std::map<uint32_t, std::vector<float>> probe_data;
  std::map<std::string, ActivationRange> recorded;
  PoolPtr pool;
  std::vector<float> input;
  std::vector<Piece> pieces;
  TailSplit split;
  std::vector<JoinedOutput> joined;  // what the host reads, fixed in place before the tails
  // The decoding tail (empty for a model whose outputs XNNPACK computes) per batch size; its
  // outputs 0 and 1 are the boxes and the scores. `last_tail` ran last.
  std::unique_ptr<DecodingTail> single_tail;
  std::unique_ptr<DecodingTail> batched_tail;
  const DecodingTail* last_tail{nullptr};
  // Each batch size twice: on the pool and on the caller's thread alone (no pool), the governor
  // choosing per pass (detector/pool_governor.hpp). Without a pool only the inline ones exist.
  RuntimePtr single_pooled;
  RuntimePtr single_inline;
  RuntimePtr batched_pooled;
  RuntimePtr batched_inline;
  PoolGovernor single_governor;
  PoolGovernor batched_governor;
  std::string summary;
};

XnnpackNetwork::XnnpackNetwork(const XnnpackNetworkConfig& config)
    : impl_(std::make_unique<Impl>()) {
  Impl& impl = *impl_;
  impl.config = config;
  const auto& path = config.model_path;
  const auto model_error = [&](const std::string& problem) {
    return InputError(path.string(), 0, "", problem, ExitCode::bad_model);
  };
  if (xnn_initialize(nullptr) != xnn_status_success) {
    throw model_error("XNNPACK does not run on this processor");
  }
  std::string bytes;
  try {
    bytes = read_text_file(path, kMaxModelBytes);
  } catch (const InputError& e) {
    throw InputError(e.file(), e.line(), e.field(),
                     std::string("cannot read the model: ") + e.what(),
                     e.exit_code() == ExitCode::bad_input ? ExitCode::bad_model : e.exit_code());
  }
  if (!impl.model.ParseFromString(bytes)) {
    throw model_error("not an ONNX model (truncated or corrupt? run scripts/fetch_model.sh again)");
  }
  const bool int8 = !config.int8_ranges.empty();
  if (int8 && config.record_ranges) {
    throw model_error("ranges are recorded on the fp32 engine, not the int8 one");
  }
  if (int8 || config.record_ranges) impl.model_sha256 = sha256_hex(bytes);
  if (int8) {
    impl.ranges = read_activation_ranges(config.int8_ranges);
    check_ranges_belong_to(impl.ranges, config.int8_ranges, impl.model_sha256);
  }
  bytes = std::string();
  const onnx::GraphProto& graph = impl.model.graph();
  BuildMode mode;
  if (int8) {
    mode.ranges = &impl.ranges;
    mode.ranges_path = &config.int8_ranges;
    mode.quantized = &impl.quantized_weights;
  }
  if (config.record_ranges) mode.probes = &impl.probes;
  for (const auto& output : graph.output()) {
    if (output.name() != config.box_output && output.name() != config.logit_output) {
      throw model_error("the model has outputs other than '" + config.box_output + "' and '" +
                        config.logit_output + "'");
    }
  }
  for (const std::string& name : {config.box_output, config.logit_output}) {
    const auto& outputs = graph.output();
    if (std::none_of(outputs.begin(), outputs.end(),
                     [&](const onnx::ValueInfoProto& o) { return o.name() == name; })) {
      throw model_error("the model has no output '" + name + "'");
    }
  }
  impl.split = split_decoding_tail(path, graph, xnnpack_supported_operators());
  const auto external_ids = external_outputs(graph, impl.split.boundary);

  const auto max_batch = static_cast<std::size_t>(std::max(1, config.max_batch));
  const auto input_size = static_cast<std::size_t>(config.input_size);
  const std::size_t image_floats = input_size * input_size * 3;
  impl.input.assign(max_batch * image_floats + XNN_EXTRA_BYTES / sizeof(float), 0.F);
  // Never more workers than the CPUs this process may use (affinity mask, cpuset, CPU quota: as
  // OpenCV counts them): a pool larger than that spins on every operator for a worker that has no
  // core (measured: 2 threads on one core, 675 ms a forward against 39 ms for OpenCV).
  const int cpus = std::max(1, cv::getNumberOfCPUs());
  const int threads = config.threads > 0 ? std::min(config.threads, cpus) : cpus;
  if (threads > 1) {
    impl.pool.reset(pthreadpool_create(static_cast<std::size_t>(threads)));
    if (!impl.pool) throw model_error("cannot start XNNPACK's thread pool");
  }

  std::map<uint32_t, std::size_t> piece_sizes;  // floats per image of each external output
  const auto make_runtime = [&](std::size_t batch, std::map<std::string, Value>& outputs,
                                pthreadpool_t pool) {
    SubgraphBuilder builder(path, graph, impl.split, impl.weights, external_ids, batch, input_size,
                            mode);
    SubgraphPtr subgraph = builder.build(outputs, piece_sizes);
    xnn_runtime_t raw = nullptr;
    // Workers sleep once a forward is done instead of spinning until the next frame arrives: the
    // pipeline's capture and track threads share these cores between forwards (measured on 2 idle
    // cores: the forward's median and the every-frame FPS unchanged). Between operators they still
    // spin (the flag reaches the last operator only): hence the governor.
    const xnn_status status =
        xnn_create_runtime_v2(subgraph.get(), pool, pool ? XNN_FLAG_YIELD_WORKERS : 0, &raw);
    if (status != xnn_status_success) {
      throw model_error("XNNPACK cannot plan the network (status " +
                        std::to_string(static_cast<int>(status)) + ")");
    }
    return RuntimePtr(raw);
  };

  // Batch 1 first: it names the outputs' pieces and sizes their buffers.
  std::map<std::string, Value> outputs;
  impl.single_inline = make_runtime(1, outputs, nullptr);
  if (impl.pool) impl.single_pooled = make_runtime(1, outputs, impl.pool.get());
  std::map<uint32_t, std::size_t> piece_of;
  for (const std::string& name : impl.split.boundary) {
    JoinedOutput& joined = impl.joined.emplace_back();
    const Value& value = outputs.at(name);
    if (value.shape.size() < 2) throw model_error("the tensor '" + name + "' is not per image");
    joined.name = name;
    joined.shape = value.shape;
    joined.width = value.shape.back();
    joined.per_image = product(value.shape, 1);
    for (const uint32_t id : value.pieces) {
      if (!piece_of.count(id)) {
        piece_of[id] = impl.pieces.size();
        impl.pieces.push_back({id, 0, {}});
      }
      joined.piece_indices.push_back(piece_of[id]);
    }
    joined.data.assign(max_batch * joined.per_image, 0.F);
  }
  if (max_batch > 1) {
    impl.batched_inline = make_runtime(max_batch, outputs, nullptr);
    if (impl.pool) impl.batched_pooled = make_runtime(max_batch, outputs, impl.pool.get());
  }
  for (Piece& piece : impl.pieces) {
    piece.per_image = piece_sizes.at(piece.id);
    piece.data.assign(max_batch * piece.per_image, 0.F);
  }
  for (const JoinedOutput& joined : impl.joined) {
    std::size_t sum = 0;
    for (const std::size_t index : joined.piece_indices) sum += impl.pieces[index].per_image;
    if (sum != joined.per_image) throw model_error("the outputs' pieces do not add up");
  }
  const auto tail_for = [&](std::size_t batch) {
    std::vector<TailInput> inputs;
    for (const JoinedOutput& joined : impl.joined) {
      std::vector<std::size_t> shape = joined.shape;
      shape[0] = batch;
      inputs.push_back({joined.name, shape, joined.data.data()});
    }
    auto tail = std::make_unique<DecodingTail>(
        path, impl.model, impl.split, inputs,
        std::vector<std::string>{config.box_output, config.logit_output});
    for (std::size_t output = 0; output < 2; ++output) {
      const auto& shape = tail->output_shape(output);
      if (shape.size() < 2 || shape[0] != batch) {
        throw model_error("the output '" + (output == 0 ? config.box_output : config.logit_output) +
                          "' is not per image (" + shape_text(shape) + " at batch " +
                          std::to_string(batch) + ")");
      }
    }
    return tail;
  };
  impl.single_tail = tail_for(1);
  if (max_batch > 1) impl.batched_tail = tail_for(max_batch);
  impl.last_tail = impl.single_tail.get();
  // The buffers never move: set up once, each run only invokes.
  std::vector<xnn_external_value> externals{{kInputExternalId, impl.input.data()}};
  for (Piece& piece : impl.pieces) externals.push_back({piece.id, piece.data.data()});
  for (const auto& [name, id] : impl.probes) {
    (void)name;
    if (id == kInputExternalId || piece_of.count(id)) continue;  // buffers of their own
    auto& data = impl.probe_data[id];
    data.assign(max_batch * piece_sizes.at(id), 0.F);
    externals.push_back({id, data.data()});
  }
  for (xnn_runtime_t runtime : {impl.single_pooled.get(), impl.single_inline.get(),
                                impl.batched_pooled.get(), impl.batched_inline.get()}) {
    if (runtime &&
        xnn_setup_runtime(runtime, externals.size(), externals.data()) != xnn_status_success) {
      throw model_error("XNNPACK cannot set up the network's buffers");
    }
  }
  std::map<std::string, int> ops;
  for (const auto& node : graph.node()) ++ops[node.op_type()];
  std::ostringstream text;
  text << "XNNPACK subgraph of " << graph.node_size() << " ONNX nodes (";
  bool first = true;
  for (const auto& [op, n] : ops) {
    text << (first ? "" : ", ") << n << " " << op;
    first = false;
  }
  text << ")" << (int8 ? ", int8 (ranges " + config.int8_ranges.string() + ")" : std::string())
       << (config.record_ranges ? ", recording ranges" : "") << ", batch 1"
       << (max_batch > 1 ? " and " + std::to_string(max_batch) : std::string()) << ", " << threads
       << " thread(s)"
       << (config.threads > threads
               ? " (" + std::to_string(config.threads) + " asked; the CPUs this process may use)"
               : std::string())
       << (impl.pool ? ", the pool used while faster than one thread (measured pass by pass)" : "")
       << (impl.split.empty() ? std::string()
                              : ", then a decoding tail of " +
                                    std::to_string(impl.split.tail_nodes) + " nodes on the host");
  impl.summary = text.str();
}

XnnpackNetwork::~XnnpackNetwork() = default;

float* XnnpackNetwork::input(int slot) {
  const auto size = static_cast<std::size_t>(impl_->config.input_size);
  return impl_->input.data() + static_cast<std::size_t>(slot) * size * size * 3;
}

void XnnpackNetwork::run(int count) {
  Impl& impl = *impl_;
  const bool batched = count > 1 && impl.batched_inline;
  PoolGovernor& governor = batched ? impl.batched_governor : impl.single_governor;
  const bool pooled = impl.pool && governor.use_pool();
  xnn_runtime_t runtime = batched ? (pooled ? impl.batched_pooled : impl.batched_inline).get()
                                  : (pooled ? impl.single_pooled : impl.single_inline).get();
  const auto start = std::chrono::steady_clock::now();
  if (xnn_invoke_runtime(runtime) != xnn_status_success) {
    throw std::runtime_error("XNNPACK failed to run the network");
  }
  if (impl.pool) {
    governor.record(std::chrono::duration_cast<std::chrono::nanoseconds>(
                        std::chrono::steady_clock::now() - start)
                        .count());
  }
  if (!impl.probes.empty()) record_ranges(count);
  // The concatenations the network ends with, image by image; then the decoding tail.
  for (JoinedOutput& joined : impl.joined) {
    for (int image = 0; image < count; ++image) {
      float* to = joined.data.data() + static_cast<std::size_t>(image) * joined.per_image;
      for (const std::size_t index : joined.piece_indices) {
        const Piece& piece = impl.pieces[index];
        const float* from = piece.data.data() + static_cast<std::size_t>(image) * piece.per_image;
        to = std::copy(from, from + piece.per_image, to);
      }
    }
  }
  impl.last_tail = (batched ? impl.batched_tail : impl.single_tail).get();
  impl.last_tail->run();
}

void XnnpackNetwork::record_ranges(int count) {
  Impl& impl = *impl_;
  const auto image_floats =
      static_cast<std::size_t>(impl.config.input_size) * impl.config.input_size * 3;
  for (const auto& [name, id] : impl.probes) {
    const float* data = nullptr;
    std::size_t size = 0;
    if (id == kInputExternalId) {
      data = impl.input.data();
      size = image_floats;
    } else if (const auto probe = impl.probe_data.find(id); probe != impl.probe_data.end()) {
      data = probe->second.data();
      size = probe->second.size() / static_cast<std::size_t>(std::max(1, impl.config.max_batch));
    } else {
      for (const Piece& piece : impl.pieces) {
        if (piece.id == id) {
          data = piece.data.data();
          size = piece.per_image;
        }
      }
    }
    if (!data || size == 0) continue;
    const auto [low, high] =
        std::minmax_element(data, data + size * static_cast<std::size_t>(count));
    auto [range, fresh] = impl.recorded.try_emplace(name, ActivationRange{*low, *high});
    if (!fresh) {
      range->second.min = std::min(range->second.min, *low);
      range->second.max = std::max(range->second.max, *high);
    }
  }
}

ActivationRanges XnnpackNetwork::recorded_ranges() const {
  ActivationRanges ranges;
  ranges.model_sha256 = impl_->model_sha256;
  ranges.tensors = impl_->recorded;
  return ranges;
}

void XnnpackNetwork::clear_recorded_ranges() {
  impl_->recorded.clear();
}

const float* XnnpackNetwork::boxes() const {
  return impl_->last_tail->output(0);
}
const float* XnnpackNetwork::logits() const {
  return impl_->last_tail->output(1);
}
std::size_t XnnpackNetwork::anchors() const {
  const auto& shape = impl_->single_tail->output_shape(0);
  return product(shape, 1) / std::max<std::size_t>(shape.back(), 1);
}
std::size_t XnnpackNetwork::classes() const {
  return impl_->single_tail->output_shape(1).back();
}
std::string XnnpackNetwork::summary() const {
  return impl_->summary;
}

std::string XnnpackNetwork::pool_use() const {
  if (!impl_->pool) return "";
  std::ostringstream text;
  text.precision(3);
  for (const auto& [name, governor] : {std::pair{"batch 1", &impl_->single_governor},
                                       std::pair{"batch", &impl_->batched_governor}}) {
    if (governor->passes() == 0) continue;
    text << (text.tellp() > 0 ? "; " : "") << name << ": " << governor->pooled_passes() << " of "
         << governor->passes() << " passes on the pool (estimates: pool "
         << static_cast<double>(governor->pooled_ns()) * 1e-6 << " ms, one thread "
         << static_cast<double>(governor->inline_ns()) * 1e-6 << " ms)";
  }
  return text.str();
}

}  // namespace rtmot::detector
