// The decoding tail's planner (xnnpack_tail_planner.hpp): the tensors by name, the dispatch by
// operator, a node's inputs, constants, results and steps.
#include "detector/xnnpack_tail_planner.hpp"

#include <algorithm>
#include <cstring>

#include "detector/xnnpack_onnx_reading.hpp"

namespace rtmot::detector::xnnpack::tail {

void Planner::add_initializer(const onnx::TensorProto& tensor) {
  tensors_[tensor.name()] = constant_of(tensor, "initializer '" + tensor.name() + "'");
}

void Planner::add_input(const TailInput& input) {
  Tensor tensor;
  tensor.shape = input.shape;
  tensor.data = input.data;
  tensors_[input.name] = tensor;
}

const Tensor& Planner::find(const std::string& name, const onnx::NodeProto* node) const {
  const auto found = tensors_.find(name);
  if (found == tensors_.end()) {
    throw problem(node, "reads '" + name + "', which neither the network nor the tail computes");
  }
  return found->second;
}

void Planner::plan(const onnx::NodeProto& node) {
  const std::string& op = node.op_type();
  if (op == "Constant") {
    constant_node(node);
  } else if (op == "Identity") {
    alias(node, input(node, 0).shape);
  } else if (op == "Reshape") {
    reshape(node);
  } else if (op == "Unsqueeze" || op == "Squeeze") {
    squeeze(node, op == "Unsqueeze");
  } else if (op == "Flatten") {
    flatten(node);
  } else if (is_binary(op)) {
    binary(node);
  } else if (op == "Exp" || op == "Sigmoid") {
    unary(node);
  } else if (op == "Softmax") {
    softmax(node);
  } else if (op == "Slice") {
    slice(node);
  } else if (op == "Concat" && input(node, 0).integer) {
    integer_concat(node);
  } else if (op == "Concat") {
    concat(node);
  } else if (op == "Shape") {
    shape_of(node);
  } else if (op == "Gather") {
    gather(node);
  } else if (op == "Cast") {
    cast(node);
  } else {
    throw problem(&node, "op '" + op + "' in the decoding tail is run neither by XNNPACK nor by " +
                             "the host (it runs " + decoding_tail_operators() + ")");
  }
}

InputError Planner::problem(const onnx::NodeProto* node, const std::string& what) const {
  const std::string where =
      node ? "node '" + node->name() + "' (" + node->op_type() + ") of the decoding tail: "
           : std::string("the decoding tail: ");
  return InputError(model_.string(), 0, "", where + what, ExitCode::bad_model);
}

const Tensor& Planner::input(const onnx::NodeProto& node, int index) const {
  if (index >= node.input_size() || node.input(index).empty()) {
    throw problem(&node, "input " + std::to_string(index) + " missing");
  }
  return find(node.input(index), &node);
}

const Tensor& Planner::floats_input(const onnx::NodeProto& node, int index) const {
  const Tensor& tensor = input(node, index);
  if (tensor.integer) throw problem(&node, "integer arithmetic is not run by the tail");
  return tensor;
}

std::vector<std::int64_t> Planner::integers_input(const onnx::NodeProto& node, int index) const {
  const Tensor& tensor = input(node, index);
  if (!tensor.integer)
    throw problem(&node, "input '" + node.input(index) + "' must be int64 constants");
  return tensor.integers;
}

std::vector<std::int64_t> Planner::ints_attribute(const onnx::NodeProto& node,
                                                  const char* name) const {
  const auto* a = attribute(node, name);
  if (!a) return {};
  return {a->ints().begin(), a->ints().end()};
}

std::int64_t Planner::axis_in(const onnx::NodeProto& node, std::int64_t axis,
                              std::size_t rank) const {
  const auto r = static_cast<std::int64_t>(rank);
  if (axis < 0) axis += r;
  if (axis < 0 || axis >= r) {
    throw problem(&node, "axis " + std::to_string(axis) + " outside a tensor of rank " +
                             std::to_string(rank));
  }
  return axis;
}

Tensor Planner::constant_of(const onnx::TensorProto& proto, const std::string& what) {
  Tensor tensor;
  tensor.constant = true;
  for (const auto dim : proto.dims()) {
    if (dim < 0 || dim > (std::int64_t{1} << 24)) {
      throw problem(nullptr, what + " declares a dimension of " + std::to_string(dim));
    }
    tensor.shape.push_back(static_cast<std::size_t>(dim));
  }
  const std::size_t count = element_count(proto);
  const std::string& raw = proto.raw_data();
  if (proto.data_type() == onnx::TensorProto::FLOAT) {
    auto& data = buffers_.emplace_back(count, 0.F);
    if (!raw.empty() && raw.size() == count * sizeof(float)) {
      std::memcpy(data.data(), raw.data(), raw.size());
    } else if (raw.empty() && static_cast<std::size_t>(proto.float_data_size()) == count) {
      std::copy(proto.float_data().begin(), proto.float_data().end(), data.begin());
    } else {
      throw problem(nullptr,
                    what + " holds the wrong number of values for " + shape_text(tensor.shape));
    }
    tensor.data = data.data();
  } else if (proto.data_type() == onnx::TensorProto::INT64) {
    tensor.integer = true;
    tensor.integers.resize(count);
    if (!raw.empty() && raw.size() == count * sizeof(std::int64_t)) {
      std::memcpy(tensor.integers.data(), raw.data(), raw.size());
    } else if (raw.empty() && static_cast<std::size_t>(proto.int64_data_size()) == count) {
      std::copy(proto.int64_data().begin(), proto.int64_data().end(), tensor.integers.begin());
    } else {
      throw problem(nullptr,
                    what + " holds the wrong number of values for " + shape_text(tensor.shape));
    }
  } else {
    throw problem(nullptr, what + " is neither float32 nor int64");
  }
  return tensor;
}

Tensor& Planner::result(const onnx::NodeProto& node, const Shape& shape, bool constant) {
  if (product(shape) > (std::size_t{1} << 26) || shape.size() > kMaxRank) {
    throw problem(&node, "would compute " + shape_text(shape) + " values");
  }
  Tensor& tensor = tensors_[node.output(0)];
  tensor = Tensor();
  tensor.shape = shape;
  tensor.constant = constant;
  tensor.data = buffers_.emplace_back(product(shape), 0.F).data();
  return tensor;
}

void Planner::schedule(bool constant, std::function<void()> step) {
  if (constant) {
    step();
  } else {
    steps_.push_back(std::move(step));
  }
}

void Planner::constant_node(const onnx::NodeProto& node) {
  Tensor tensor;
  if (const auto* a = attribute(node, "value")) {
    tensor = constant_of(a->t(), "the constant '" + node.output(0) + "'");
  } else if (const auto* f = attribute(node, "value_float")) {
    tensor.constant = true;
    tensor.data = buffers_.emplace_back(1, f->f()).data();
  } else if (const auto* fs = attribute(node, "value_floats")) {
    tensor.constant = true;
    tensor.shape = {static_cast<std::size_t>(fs->floats_size())};
    tensor.data = buffers_.emplace_back(fs->floats().begin(), fs->floats().end()).data();
  } else if (const auto* i = attribute(node, "value_int")) {
    tensor.constant = tensor.integer = true;
    tensor.integers = {i->i()};
  } else if (const auto* is = attribute(node, "value_ints")) {
    tensor.constant = tensor.integer = true;
    tensor.shape = {static_cast<std::size_t>(is->ints_size())};
    tensor.integers.assign(is->ints().begin(), is->ints().end());
  } else {
    throw problem(&node, "a Constant of a kind the tail does not read");
  }
  tensors_[node.output(0)] = tensor;
}

}  // namespace rtmot::detector::xnnpack::tail
