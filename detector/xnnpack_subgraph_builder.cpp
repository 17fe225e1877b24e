#include "detector/xnnpack_subgraph_builder.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "detector/xnnpack_network.hpp"
#include "detector/xnnpack_onnx_reading.hpp"

namespace rtmot::detector::xnnpack {

SubgraphBuilder::SubgraphBuilder(const std::filesystem::path& path, const onnx::GraphProto& graph,
                                 const TailSplit& split,
                                 std::map<std::string, std::vector<float>>& weights,
                                 const std::map<std::string, uint32_t>& external_ids,
                                 std::size_t batch, std::size_t input_size, BuildMode mode)
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

SubgraphPtr SubgraphBuilder::build(std::map<std::string, Value>& outputs,
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

InputError SubgraphBuilder::model_error(const std::string& problem) const {
  return InputError(path_.string(), 0, "", problem, ExitCode::bad_model);
}

InputError SubgraphBuilder::error(const onnx::NodeProto& node, const std::string& problem) const {
  return model_error("node '" + node.name() + "' (" + node.op_type() + "): " + problem);
}

void SubgraphBuilder::check(xnn_status status, const std::string& what) const {
  if (status != xnn_status_success) {
    throw model_error("XNNPACK cannot " + what + " (status " +
                      std::to_string(static_cast<int>(status)) + ")");
  }
}

void SubgraphBuilder::define_input() {
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
    if (ok && dims[i].has_dim_value() && static_cast<std::size_t>(dims[i].dim_value()) != want[i]) {
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

const Value& SubgraphBuilder::value_of(const onnx::NodeProto& node, int input) const {
  if (input >= node.input_size()) throw error(node, "input " + std::to_string(input) + " missing");
  const auto found = values_.find(node.input(input));
  if (found == values_.end()) {
    throw error(node, "input '" + node.input(input) +
                          "' is not computed by an earlier node (constant activations are not "
                          "supported by the xnnpack backend)");
  }
  return found->second;
}

const Value& SubgraphBuilder::xnn_value_of(const onnx::NodeProto& node, int input) const {
  const Value& value = value_of(node, input);
  if (!value.xnn_shape || !value.pieces.empty()) {
    throw error(node,
                "reads a reshaped or concatenated tensor; the xnnpack backend joins those "
                "only at the graph's outputs");
  }
  return value;
}

const onnx::TensorProto& SubgraphBuilder::initializer(const onnx::NodeProto& node,
                                                      int input) const {
  if (input >= node.input_size()) throw error(node, "input " + std::to_string(input) + " missing");
  const auto found = initializers_.find(node.input(input));
  if (found == initializers_.end()) {
    throw error(node, "input '" + node.input(input) + "' must be a constant (initializer)");
  }
  return *found->second;
}

std::vector<float> SubgraphBuilder::floats(const onnx::NodeProto& node,
                                           const onnx::TensorProto& tensor) const {
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
                            std::to_string(dim) + " (at most " + std::to_string(kMaxDeclaredSize) +
                            ")");
    }
  }
  std::vector<std::size_t> dims(tensor.dims().begin(), tensor.dims().end());
  if (data.size() != product(dims)) {
    throw error(node, "weight tensor '" + tensor.name() + "' holds " + std::to_string(data.size()) +
                          " values for shape " + shape_text(dims));
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

std::vector<std::int64_t> SubgraphBuilder::int64s(const onnx::NodeProto& node,
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

uint32_t SubgraphBuilder::define_static(const std::string& key,
                                        const std::vector<std::size_t>& dims,
                                        const std::vector<float>& data) {
  auto& stored = weights_[key];
  if (stored.empty()) stored = data;
  uint32_t id = XNN_INVALID_VALUE_ID;
  check(xnn_define_tensor_value(subgraph_, xnn_datatype_fp32, dims.size(), dims.data(),
                                stored.data(), XNN_INVALID_VALUE_ID, 0, &id),
        "define the weights '" + key + "'");
  return id;
}

void SubgraphBuilder::check_size(const std::string& name,
                                 const std::vector<std::size_t>& xnn_dims) const {
  if (xnn_dims.empty() || product(xnn_dims, 1) > kMaxTensorFloatsPerImage) {
    throw model_error("the tensor '" + name + "' would be " + shape_text(xnn_dims) +
                      " floats; at most " + std::to_string(kMaxTensorFloatsPerImage) +
                      " an image (damaged model? run scripts/fetch_model.sh again)");
  }
}

uint32_t SubgraphBuilder::define_computed(const std::string& name,
                                          const std::vector<std::size_t>& xnn_dims) {
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

std::vector<std::size_t> SubgraphBuilder::xnn_dims(const Value& value) const {
  if (!value.nchw) return value.shape;
  return {value.shape[0], value.shape[2], value.shape[3], value.shape[1]};
}

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

}  // namespace rtmot::detector::xnnpack
