// The decoding tail's operators that compute floats (xnnpack_tail_planner.hpp): each a step run
// every pass, or once when its inputs are constants.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "detector/xnnpack_onnx_reading.hpp"
#include "detector/xnnpack_tail_planner.hpp"

namespace rtmot::detector::xnnpack::tail {

void Planner::binary(const onnx::NodeProto& node) {
  const Tensor a = floats_input(node, 0);
  const Tensor b = floats_input(node, 1);
  const std::size_t rank = std::max(a.shape.size(), b.shape.size());
  Shape shape(rank, 1);
  std::array<std::vector<std::size_t>, 2> strides{std::vector<std::size_t>(rank, 0),
                                                  std::vector<std::size_t>(rank, 0)};
  std::size_t k = 0;
  for (const Tensor* operand : {&a, &b}) {
    const auto own = strides_of(operand->shape);
    const std::size_t shift = rank - operand->shape.size();
    for (std::size_t i = 0; i < operand->shape.size(); ++i) {
      const std::size_t dim = operand->shape[i];
      std::size_t& out = shape[shift + i];
      if (dim != 1 && out != 1 && dim != out) {
        throw problem(&node,
                      "cannot broadcast " + shape_text(a.shape) + " with " + shape_text(b.shape));
      }
      if (dim != 1) out = dim;
      strides[k][shift + i] = dim == 1 ? 0 : own[i];
    }
    ++k;
  }
  const bool constant = a.constant && b.constant;
  float* out = writable(result(node, shape, constant));
  const float* x = a.data;
  const float* y = b.data;
  const auto run = [=](auto f) {
    return [=] {
      for_each_element<2>(shape, strides,
                          [&](std::size_t at, const std::array<std::size_t, 2>& base,
                              std::size_t row, const std::array<std::size_t, 2>& step) {
                            const float* p = x + base[0];
                            const float* q = y + base[1];
                            for (std::size_t i = 0; i < row; ++i)
                              out[at + i] = f(p[i * step[0]], q[i * step[1]]);
                          });
    };
  };
  const std::string& op = node.op_type();
  if (op == "Add") {
    schedule(constant, run([](float p, float q) { return p + q; }));
  } else if (op == "Sub") {
    schedule(constant, run([](float p, float q) { return p - q; }));
  } else if (op == "Mul") {
    schedule(constant, run([](float p, float q) { return p * q; }));
  } else {
    schedule(constant, run([](float p, float q) { return p / q; }));
  }
}

void Planner::unary(const onnx::NodeProto& node) {
  const Tensor a = floats_input(node, 0);
  float* out = writable(result(node, a.shape, a.constant));
  const float* x = a.data;
  const std::size_t n = product(a.shape);
  if (node.op_type() == "Exp") {
    schedule(a.constant, [=] {
      for (std::size_t i = 0; i < n; ++i) out[i] = std::exp(x[i]);
    });
  } else {
    schedule(a.constant, [=] {
      for (std::size_t i = 0; i < n; ++i) out[i] = 1.F / (1.F + std::exp(-x[i]));
    });
  }
}

void Planner::softmax(const onnx::NodeProto& node) {
  const Tensor a = floats_input(node, 0);
  const auto* at = attribute(node, "axis");
  const std::size_t axis = static_cast<std::size_t>(
      axis_in(node, at ? at->i() : (opset_ < 13 ? 1 : -1), a.shape.size()));
  const std::size_t outer = product(a.shape, 0, axis);
  const std::size_t length = opset_ < 13 ? product(a.shape, axis) : a.shape[axis];
  const std::size_t inner = opset_ < 13 ? 1 : product(a.shape, axis + 1);
  float* out = writable(result(node, a.shape, a.constant));
  const float* x = a.data;
  schedule(a.constant, [=] {
    for (std::size_t o = 0; o < outer; ++o) {
      for (std::size_t i = 0; i < inner; ++i) {
        const std::size_t first = o * length * inner + i;
        float largest = -std::numeric_limits<float>::infinity();
        for (std::size_t k = 0; k < length; ++k) largest = std::max(largest, x[first + k * inner]);
        float sum = 0.F;
        for (std::size_t k = 0; k < length; ++k) {
          out[first + k * inner] = std::exp(x[first + k * inner] - largest);
          sum += out[first + k * inner];
        }
        for (std::size_t k = 0; k < length; ++k) out[first + k * inner] /= sum;
      }
    }
  });
}

void Planner::slice(const onnx::NodeProto& node) {
  const Tensor a = floats_input(node, 0);
  const std::size_t rank = a.shape.size();
  std::vector<std::int64_t> starts;
  std::vector<std::int64_t> ends;
  std::vector<std::int64_t> axes;
  std::vector<std::int64_t> steps;
  if (opset_ < 10) {
    starts = ints_attribute(node, "starts");
    ends = ints_attribute(node, "ends");
    axes = ints_attribute(node, "axes");
  } else {
    starts = integers_input(node, 1);
    ends = integers_input(node, 2);
    if (node.input_size() > 3 && !node.input(3).empty()) axes = integers_input(node, 3);
    if (node.input_size() > 4 && !node.input(4).empty()) steps = integers_input(node, 4);
  }
  if (axes.empty()) {
    for (std::size_t i = 0; i < starts.size(); ++i) axes.push_back(static_cast<std::int64_t>(i));
  }
  if (steps.empty()) steps.assign(starts.size(), 1);
  if (ends.size() != starts.size() || axes.size() != starts.size() ||
      steps.size() != starts.size()) {
    throw problem(&node, "starts, ends, axes and steps of different lengths");
  }
  Shape shape = a.shape;
  std::vector<std::size_t> first(rank, 0);
  std::vector<std::size_t> stride(rank, 1);
  for (std::size_t i = 0; i < starts.size(); ++i) {
    const auto axis = static_cast<std::size_t>(axis_in(node, axes[i], rank));
    if (steps[i] < 1) throw problem(&node, "only positive steps are run by the tail");
    const auto dim = static_cast<std::int64_t>(a.shape[axis]);
    const auto clamp = [dim](std::int64_t v) {
      return std::clamp(v < 0 ? v + dim : v, std::int64_t{0}, dim);
    };
    const std::int64_t begin = clamp(starts[i]);
    const std::int64_t end = clamp(ends[i]);
    first[axis] = static_cast<std::size_t>(begin);
    stride[axis] = static_cast<std::size_t>(steps[i]);
    shape[axis] =
        end > begin ? static_cast<std::size_t>((end - begin + steps[i] - 1) / steps[i]) : 0;
  }
  const auto own = strides_of(a.shape);
  std::size_t offset = 0;
  std::array<std::vector<std::size_t>, 1> strides{std::vector<std::size_t>(rank)};
  for (std::size_t i = 0; i < rank; ++i) {
    offset += first[i] * own[i];
    strides[0][i] = own[i] * stride[i];
  }
  float* out = writable(result(node, shape, a.constant));
  const float* x = a.data + offset;
  schedule(a.constant, [=] {
    for_each_element<1>(shape, strides,
                        [&](std::size_t at, const std::array<std::size_t, 1>& base, std::size_t row,
                            const std::array<std::size_t, 1>& step) {
                          for (std::size_t i = 0; i < row; ++i)
                            out[at + i] = x[base[0] + i * step[0]];
                        });
  });
}

void Planner::concat(const onnx::NodeProto& node) {
  const auto* a = attribute(node, "axis");
  if (!a) throw problem(&node, "no axis");
  std::vector<Tensor> parts;
  for (int i = 0; i < node.input_size(); ++i) parts.push_back(floats_input(node, i));
  const std::size_t rank = parts.front().shape.size();
  const auto axis = static_cast<std::size_t>(axis_in(node, a->i(), rank));
  Shape shape = parts.front().shape;
  shape[axis] = 0;
  bool constant = true;
  for (const Tensor& part : parts) {
    Shape other = part.shape;
    if (other.size() != rank) throw problem(&node, "inputs of different ranks");
    shape[axis] += other[axis];
    other[axis] = shape[axis];
    Shape mine = shape;
    if (other != mine) {
      throw problem(&node, "inputs " + shape_text(parts.front().shape) + " and " +
                               shape_text(part.shape) + " differ outside axis " +
                               std::to_string(axis));
    }
    constant = constant && part.constant;
  }
  const std::size_t outer = product(shape, 0, axis);
  std::vector<std::pair<const float*, std::size_t>> pieces;  // data, floats per outer index
  for (const Tensor& part : parts) pieces.emplace_back(part.data, product(part.shape, axis));
  const std::size_t row = product(shape, axis);
  float* out = writable(result(node, shape, constant));
  schedule(constant, [=] {
    for (std::size_t o = 0; o < outer; ++o) {
      float* to = out + o * row;
      for (const auto& [data, size] : pieces)
        to = std::copy(data + o * size, data + (o + 1) * size, to);
    }
  });
}

}  // namespace rtmot::detector::xnnpack::tail
