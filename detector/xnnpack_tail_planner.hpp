#pragma once
// The decoding tail's planner (xnnpack_decoding_tail.hpp): DecodingTail's constructor hands it the
// tail's nodes in graph order; it names every tensor, sizes every buffer, computes what depends on
// constants alone, and appends a step for each of the rest. Its definitions are in three files:
// xnnpack_tail_planner.cpp (the tensors by name, a node's inputs, constants, results and steps),
// xnnpack_tail_float_operators.cpp (the operators that compute floats: Add, Sub, Mul, Div, Exp,
// Sigmoid, Softmax, Slice, Concat) and xnnpack_tail_shape_operators.cpp (those that compute none:
// views such as Reshape, and Shape, Gather, Cast, Concat on shapes). Internal to detector/.
#include <onnx/onnx_pb.h>

#include <cstdint>
#include <deque>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "common/input_error.hpp"
#include "detector/xnnpack_decoding_tail.hpp"
#include "detector/xnnpack_tail_tensors.hpp"

namespace rtmot::detector::xnnpack::tail {

/// Plans one tail: every tensor by name, steps appended in graph order.
class Planner {
 public:
  Planner(const std::filesystem::path& model, int opset, std::deque<std::vector<float>>& buffers,
          std::vector<std::function<void()>>& steps)
      : model_(model), opset_(opset), buffers_(buffers), steps_(steps) {}

  void add_initializer(const onnx::TensorProto& tensor);
  void add_input(const TailInput& input);
  const Tensor& find(const std::string& name, const onnx::NodeProto* node) const;

  void plan(const onnx::NodeProto& node);

  InputError problem(const onnx::NodeProto* node, const std::string& what) const;

 private:
  // xnnpack_tail_planner.cpp: a node's inputs, constants, results and steps.
  const Tensor& input(const onnx::NodeProto& node, int index) const;
  const Tensor& floats_input(const onnx::NodeProto& node, int index) const;
  std::vector<std::int64_t> integers_input(const onnx::NodeProto& node, int index) const;
  std::vector<std::int64_t> ints_attribute(const onnx::NodeProto& node, const char* name) const;
  std::int64_t axis_in(const onnx::NodeProto& node, std::int64_t axis, std::size_t rank) const;

  Tensor constant_of(const onnx::TensorProto& proto, const std::string& what);

  // A computed tensor of `shape`: its buffer, and whether its step runs now (all inputs
  // constant: the value is a constant) or every pass.
  Tensor& result(const onnx::NodeProto& node, const Shape& shape, bool constant);
  void schedule(bool constant, std::function<void()> step);
  float* writable(const Tensor& tensor) const { return const_cast<float*>(tensor.data); }

  void constant_node(const onnx::NodeProto& node);

  // xnnpack_tail_shape_operators.cpp: views, and integer constants on shapes.

  // The same values under another shape: no step.
  void alias(const onnx::NodeProto& node, const Shape& shape);

  void reshape(const onnx::NodeProto& node);
  void squeeze(const onnx::NodeProto& node, bool unsqueeze);
  void flatten(const onnx::NodeProto& node);

  // Shapes are known when the tail is planned: torch.onnx's `view(x.size(0), -1, k)` (Shape,
  // Gather, Unsqueeze, Concat, then Reshape) becomes constants here.
  void shape_of(const onnx::NodeProto& node);

  void gather(const onnx::NodeProto& node);
  void cast(const onnx::NodeProto& node);
  void integer_concat(const onnx::NodeProto& node);

  // xnnpack_tail_float_operators.cpp: the operators that compute floats, a step each.
  void binary(const onnx::NodeProto& node);
  void unary(const onnx::NodeProto& node);

  // Opset 13's Softmax normalises along one axis; earlier ones over the axes from `axis` on
  // (the input seen as 2-D), their default axis 1.
  void softmax(const onnx::NodeProto& node);

  void slice(const onnx::NodeProto& node);
  void concat(const onnx::NodeProto& node);

  const std::filesystem::path& model_;
  int opset_;
  std::deque<std::vector<float>>& buffers_;
  std::vector<std::function<void()>>& steps_;
  std::map<std::string, Tensor> tensors_;
};

}  // namespace rtmot::detector::xnnpack::tail
