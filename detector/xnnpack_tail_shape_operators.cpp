// The decoding tail's operators that compute no floats (xnnpack_tail_planner.hpp): views of a
// tensor under another shape, and int64 constants on shapes, computed once.
#include <algorithm>

#include "detector/xnnpack_onnx_reading.hpp"
#include "detector/xnnpack_tail_planner.hpp"

namespace rtmot::detector::xnnpack::tail {

void Planner::alias(const onnx::NodeProto& node, const Shape& shape) {
  Tensor tensor = input(node, 0);
  if (product(shape) != product(tensor.shape)) {
    throw problem(&node, "cannot view " + shape_text(tensor.shape) + " as " + shape_text(shape));
  }
  tensor.shape = shape;
  tensors_[node.output(0)] = tensor;
}

void Planner::reshape(const onnx::NodeProto& node) {
  const Shape& from = input(node, 0).shape;
  const auto wanted = opset_ < 5 ? ints_attribute(node, "shape") : integers_input(node, 1);
  Shape shape(wanted.size(), 1);
  int infer = -1;
  for (std::size_t i = 0; i < wanted.size(); ++i) {
    if (wanted[i] == -1 && infer < 0) {
      infer = static_cast<int>(i);
    } else if (wanted[i] == 0 && i < from.size()) {
      shape[i] = from[i];
    } else if (wanted[i] > 0) {
      shape[i] = static_cast<std::size_t>(wanted[i]);
    } else {
      throw problem(&node, "invalid target shape");
    }
  }
  if (infer >= 0) {
    const std::size_t known = product(shape);
    shape[static_cast<std::size_t>(infer)] = known ? product(from) / known : 0;
  }
  alias(node, shape);
}

void Planner::squeeze(const onnx::NodeProto& node, bool unsqueeze) {
  const Shape& from = input(node, 0).shape;
  std::vector<std::int64_t> axes = opset_ < 13 ? ints_attribute(node, "axes")
                                   : node.input_size() > 1 && !node.input(1).empty()
                                       ? integers_input(node, 1)
                                       : std::vector<std::int64_t>{};
  Shape shape;
  if (unsqueeze) {
    const std::size_t rank = from.size() + axes.size();
    std::vector<bool> inserted(rank, false);
    for (const auto axis : axes)
      inserted[static_cast<std::size_t>(axis_in(node, axis, rank))] = true;
    std::size_t next = 0;
    for (std::size_t i = 0; i < rank; ++i) shape.push_back(inserted[i] ? 1 : from.at(next++));
  } else {
    std::vector<bool> removed(from.size(), axes.empty());
    for (const auto axis : axes) {
      removed[static_cast<std::size_t>(axis_in(node, axis, from.size()))] = true;
    }
    for (std::size_t i = 0; i < from.size(); ++i) {
      if (!removed[i] || from[i] != 1) shape.push_back(from[i]);
    }
  }
  if (input(node, 0).integer) {  // index arithmetic on constants: the values stay
    Tensor tensor = input(node, 0);
    tensor.shape = shape;
    tensors_[node.output(0)] = tensor;
    return;
  }
  alias(node, shape);
}

void Planner::flatten(const onnx::NodeProto& node) {
  const Shape& from = input(node, 0).shape;
  const auto* a = attribute(node, "axis");
  const std::int64_t at = a ? a->i() : 1;
  const auto axis = static_cast<std::size_t>(
      at == static_cast<std::int64_t>(from.size()) ? at : axis_in(node, at, from.size()));
  alias(node, {product(from, 0, axis), product(from, axis)});
}

void Planner::shape_of(const onnx::NodeProto& node) {
  const Shape& from = input(node, 0).shape;
  Tensor tensor;
  tensor.constant = tensor.integer = true;
  const auto rank = static_cast<std::int64_t>(from.size());
  const auto* s = attribute(node, "start");
  const auto* e = attribute(node, "end");
  const auto clamp = [rank](std::int64_t v) {
    return std::clamp(v < 0 ? v + rank : v, std::int64_t{0}, rank);
  };
  const std::int64_t first = s ? clamp(s->i()) : 0;
  const std::int64_t last = e ? clamp(e->i()) : rank;
  for (std::int64_t i = first; i < last; ++i) {
    tensor.integers.push_back(static_cast<std::int64_t>(from[static_cast<std::size_t>(i)]));
  }
  tensor.shape = {tensor.integers.size()};
  tensors_[node.output(0)] = tensor;
}

void Planner::gather(const onnx::NodeProto& node) {
  const auto data = integers_input(node, 0);
  const Tensor& indices = input(node, 1);
  const auto* a = attribute(node, "axis");
  if (!indices.integer || input(node, 0).shape.size() != 1 || (a && a->i() != 0)) {
    throw problem(&node, "the tail gathers only from a 1-D int64 constant (a shape)");
  }
  Tensor tensor;
  tensor.constant = tensor.integer = true;
  tensor.shape = indices.shape;
  for (auto index : indices.integers) {
    const auto size = static_cast<std::int64_t>(data.size());
    if (index < 0) index += size;
    if (index < 0 || index >= size) throw problem(&node, "index outside the shape");
    tensor.integers.push_back(data[static_cast<std::size_t>(index)]);
  }
  tensors_[node.output(0)] = tensor;
}

void Planner::cast(const onnx::NodeProto& node) {
  const auto* to = attribute(node, "to");
  const Tensor& from = input(node, 0);
  const bool same = to && ((from.integer && to->i() == onnx::TensorProto::INT64) ||
                           (!from.integer && to->i() == onnx::TensorProto::FLOAT));
  if (!same) throw problem(&node, "the tail casts only int64 to int64 and float to float");
  tensors_[node.output(0)] = from;
}

void Planner::integer_concat(const onnx::NodeProto& node) {
  Tensor tensor;
  tensor.constant = tensor.integer = true;
  for (int i = 0; i < node.input_size(); ++i) {
    const auto part = integers_input(node, i);
    if (input(node, i).shape.size() > 1) throw problem(&node, "joins shapes of rank 1 only");
    tensor.integers.insert(tensor.integers.end(), part.begin(), part.end());
  }
  tensor.shape = {tensor.integers.size()};
  tensors_[node.output(0)] = tensor;
}

}  // namespace rtmot::detector::xnnpack::tail
