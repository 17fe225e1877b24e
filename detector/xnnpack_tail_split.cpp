// Where the XNNPACK engine's subgraph ends and the decoding tail begins
// (xnnpack_decoding_tail.hpp): which nodes XNNPACK's builder takes, which the host runs after it,
// and the operators each side runs.
#include <map>
#include <set>
#include <string>
#include <vector>

#include "common/input_error.hpp"
#include "detector/xnnpack_decoding_tail.hpp"
#include "detector/xnnpack_onnx_reading.hpp"
#include "detector/xnnpack_tail_tensors.hpp"

namespace rtmot::detector {

const char* decoding_tail_operators() {
  return "Slice, Mul, Add, Sub, Div, Exp, Sigmoid, Softmax, Concat, Reshape, Unsqueeze, Squeeze, "
         "Flatten, Identity, Constant; Shape, Gather, Cast on shapes (computed once)";
}

namespace {

using xnnpack::attribute;
using xnnpack::tail::element_count;
using xnnpack::tail::is_binary;

const std::set<std::string>& tail_operators() {
  static const std::set<std::string> ops{"Slice",     "Mul",     "Add",     "Sub",      "Div",
                                         "Exp",       "Sigmoid", "Softmax", "Concat",   "Reshape",
                                         "Unsqueeze", "Squeeze", "Flatten", "Identity", "Constant",
                                         "Shape",     "Gather",  "Cast"};
  return ops;
}

// What XNNPACK's builder (xnnpack_subgraph_builder.cpp) takes, by operator and by where its inputs
// come from; kept beside the split so that the two agree.
bool builder_operator(const std::string& op) {
  static const std::set<std::string> ops{"Conv", "Clip",      "Relu",    "Add",    "Mul",     "Sub",
                                         "Div",  "Transpose", "Reshape", "Concat", "Identity"};
  return ops.count(op) != 0;
}

InputError split_error(const std::filesystem::path& model, const onnx::NodeProto& node,
                       const std::string& problem) {
  return InputError(model.string(), 0, "",
                    "node '" + node.name() + "' (" + node.op_type() + "): " + problem,
                    ExitCode::bad_model);
}

}  // namespace

TailSplit split_decoding_tail(const std::filesystem::path& model, const onnx::GraphProto& graph,
                              const char* network_operators) {
  // reshaped: a Reshape's result, which XNNPACK still holds in the old shape (only a Concat or the
  // host may read it); joined: a Concat's, assembled on the host from XNNPACK's outputs.
  enum class Source { network, reshaped, joined, host, constant };
  std::map<std::string, Source> source;
  for (const auto& tensor : graph.initializer()) source[tensor.name()] = Source::constant;
  const auto source_of = [&](const std::string& name) {
    const auto found = source.find(name);
    return found == source.end() ? Source::network : found->second;  // the input
  };
  std::map<std::string, std::size_t> constant_sizes;  // initializers and Constant nodes' values
  for (const auto& tensor : graph.initializer())
    constant_sizes[tensor.name()] = element_count(tensor);
  for (const auto& node : graph.node()) {
    const auto* value = node.op_type() == "Constant" ? attribute(node, "value") : nullptr;
    if (value && node.output_size() == 1)
      constant_sizes[node.output(0)] = element_count(value->t());
  }
  const auto scalar_constant = [&](const std::string& name) {
    const auto found = constant_sizes.find(name);
    return found != constant_sizes.end() && found->second == 1;
  };
  TailSplit split;
  split.on_host.assign(static_cast<std::size_t>(graph.node_size()), false);
  std::set<std::string> boundary;
  bool convolution = false;  // a convolution among the nodes run on the host: no decoding tail
  int first_host = -1;       // the node where the host takes over
  for (int index = 0; index < graph.node_size(); ++index) {
    const onnx::NodeProto& node = graph.node(index);
    const std::string& op = node.op_type();
    bool any_host = false;
    bool any_joined = false;
    bool any_reshaped = false;
    bool all_constant = true;
    std::vector<std::string> computed;
    for (const auto& name : node.input()) {
      if (name.empty()) continue;
      const Source from = source_of(name);
      any_host = any_host || from == Source::host;
      any_joined = any_joined || from == Source::joined;
      any_reshaped = any_reshaped || from == Source::reshaped;
      all_constant = all_constant && from == Source::constant;
      if (from == Source::network || from == Source::reshaped || from == Source::joined) {
        computed.push_back(name);
      }
    }
    Source result = Source::network;
    if (all_constant) {
      result = Source::constant;  // Constant nodes, the priors' slices: computed once
    } else if (any_host || !builder_operator(op)) {
      result = Source::host;
    } else if (is_binary(op)) {
      // XNNPACK's builder: Add of two computed tensors, or any of the four with a scalar
      // constant; a per-anchor constant (the anchors' centres) belongs to the decoding.
      const bool scalar = node.input_size() == 2 &&
                          (scalar_constant(node.input(0)) || scalar_constant(node.input(1)));
      const bool two_computed = computed.size() == 2 && op == "Add";
      result =
          (scalar || two_computed) && !any_joined && !any_reshaped ? Source::network : Source::host;
    } else if (op == "Concat") {
      const auto* axis = attribute(node, "axis");
      result = axis && axis->i() == 1 && !any_joined ? Source::joined : Source::host;
    } else if (op == "Reshape") {
      result = any_joined ? Source::host : Source::reshaped;
    } else if (op == "Identity") {
      result = source_of(node.input(0));
    } else if (any_joined || any_reshaped) {
      result = Source::host;  // XNNPACK's operators read tensors in XNNPACK's own shape
    }
    if (result == Source::host || result == Source::constant) {
      split.on_host[static_cast<std::size_t>(index)] = true;
      for (const auto& name : computed) boundary.insert(name);
    }
    if (result == Source::host) {
      ++split.tail_nodes;
      if (first_host < 0) first_host = index;
      convolution = convolution || op == "Conv";
    }
    for (const auto& name : node.output()) source[name] = result;
  }
  for (const auto& output : graph.output()) {
    const Source from = source_of(output.name());
    if (from == Source::network || from == Source::reshaped || from == Source::joined) {
      boundary.insert(output.name());
    }
  }
  split.boundary.assign(boundary.begin(), boundary.end());
  // An operator neither side runs: named as the network's (a convolution follows it: it is no
  // decoding tail) or as the tail's.
  for (int index = 0; index < graph.node_size(); ++index) {
    if (!split.on_host[static_cast<std::size_t>(index)]) continue;
    const onnx::NodeProto& node = graph.node(index);
    if (tail_operators().count(node.op_type())) continue;
    if (!convolution) {
      throw split_error(model, node,
                        "op '" + node.op_type() + "' in the decoding tail: XNNPACK's engine runs " +
                            "after the network only " + decoding_tail_operators() +
                            " (on the host): use backend: cpu");
    }
    if (builder_operator(node.op_type())) {
      const onnx::NodeProto& cause = graph.node(first_host);
      throw split_error(model, node,
                        "follows node '" + cause.name() + "' (" + cause.op_type() +
                            "), which the xnnpack backend runs only on the host (it builds " +
                            network_operators +
                            "; Add, Mul, Sub, Div only with one-value "
                            "constants; nothing after a Concat or a Reshape but the heads' "
                            "join): use backend: cpu");
    }
    throw split_error(model, node,
                      "operator '" + node.op_type() +
                          "' is not supported by the xnnpack backend (it builds " +
                          network_operators + "): use backend: cpu");
  }
  return split;
}

}  // namespace rtmot::detector
