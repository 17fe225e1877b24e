#include "detector/xnnpack_decoding_tail.hpp"

#include <set>

#include "detector/xnnpack_tail_planner.hpp"

namespace rtmot::detector {

namespace {

using xnnpack::tail::Planner;

int model_opset(const onnx::ModelProto& model) {
  for (const auto& entry : model.opset_import()) {
    if (entry.domain().empty() || entry.domain() == "ai.onnx") {
      return static_cast<int>(entry.version());
    }
  }
  return 1;
}

}  // namespace

DecodingTail::DecodingTail(const std::filesystem::path& model, const onnx::ModelProto& onnx_model,
                           const TailSplit& split, const std::vector<TailInput>& inputs,
                           const std::vector<std::string>& outputs) {
  const onnx::GraphProto& graph = onnx_model.graph();
  Planner planner(model, model_opset(onnx_model), buffers_, steps_);
  std::set<std::string> read;
  for (int index = 0; index < graph.node_size(); ++index) {
    if (!split.on_host[static_cast<std::size_t>(index)]) continue;
    for (const auto& name : graph.node(index).input()) read.insert(name);
  }
  for (const auto& tensor : graph.initializer()) {
    if (read.count(tensor.name())) planner.add_initializer(tensor);
  }
  for (const TailInput& input : inputs) planner.add_input(input);
  for (int index = 0; index < graph.node_size(); ++index) {
    if (split.on_host[static_cast<std::size_t>(index)]) planner.plan(graph.node(index));
  }
  for (const std::string& name : outputs) {
    const Tensor& tensor = planner.find(name, nullptr);
    if (tensor.integer || tensor.constant) {
      throw planner.problem(nullptr, "the output '" + name + "' is a constant");
    }
    outputs_.push_back(tensor);
  }
}

void DecodingTail::run() const {
  for (const auto& step : steps_) step();
}

}  // namespace rtmot::detector
