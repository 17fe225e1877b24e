#pragma once
// What the decoding tail's files (xnnpack_decoding_tail.hpp) share: the tensors the tail computes,
// their shapes and sizes, and the loop over their elements that its steps run every pass (so it is
// defined here, inline, where the steps are made). Internal to detector/.
//
// In rtmot::detector::xnnpack::tail, apart from xnnpack_onnx_reading.hpp's product and shape_text,
// which are other functions: those saturate and write 2x3, these multiply a range of axes and
// write [2, 3] (the tail's messages).
#include <onnx/onnx_pb.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

#include "detector/xnnpack_decoding_tail.hpp"

namespace rtmot::detector::xnnpack::tail {

using Tensor = DecodingTail::Tensor;
using Shape = std::vector<std::size_t>;
constexpr std::size_t kMaxRank = 8;  // of a tensor the tail computes

// The four arithmetic operators, which the split (XNNPACK's builder takes them with a scalar)
// and the planner single out.
inline bool is_binary(const std::string& op) {
  return op == "Add" || op == "Mul" || op == "Sub" || op == "Div";
}

inline std::size_t element_count(const onnx::TensorProto& tensor) {
  std::size_t n = 1;
  for (const auto dim : tensor.dims())
    n *= static_cast<std::size_t>(std::max<std::int64_t>(dim, 0));
  return n;
}

inline std::size_t product(const Shape& shape, std::size_t from = 0,
                           std::size_t to = std::numeric_limits<std::size_t>::max()) {
  const std::size_t end = std::min(to, shape.size());
  if (from >= end) return 1;
  return std::accumulate(shape.begin() + static_cast<std::ptrdiff_t>(from),
                         shape.begin() + static_cast<std::ptrdiff_t>(end), std::size_t{1},
                         std::multiplies<>());
}

inline std::string shape_text(const Shape& shape) {
  std::string text = "[";
  for (std::size_t i = 0; i < shape.size(); ++i) text += (i ? ", " : "") + std::to_string(shape[i]);
  return text + "]";
}

inline std::vector<std::size_t> strides_of(const Shape& shape) {
  std::vector<std::size_t> strides(shape.size(), 1);
  for (std::size_t i = shape.size(); i-- > 1;) strides[i - 1] = strides[i] * shape[i];
  return strides;
}

// Visits every element of `shape` in order, with each operand's offset (its strides, 0 along a
// broadcast axis): the innermost axis as a plain loop, the others by an odometer.
template <std::size_t N, typename Visit>
void for_each_element(const Shape& shape, const std::array<std::vector<std::size_t>, N>& strides,
                      Visit visit) {
  const std::size_t rank = shape.size();
  if (product(shape) == 0) return;
  if (rank == 0) {
    std::array<std::size_t, N> offsets{};
    visit(std::size_t{0}, offsets, std::size_t{1}, offsets);
    return;
  }
  std::array<std::size_t, kMaxRank> index{};
  std::array<std::size_t, N> base{};
  std::array<std::size_t, N> inner{};
  for (std::size_t k = 0; k < N; ++k) inner[k] = strides[k][rank - 1];
  const std::size_t row = shape[rank - 1];
  std::size_t out = 0;
  while (true) {
    visit(out, base, row, inner);
    out += row;
    std::size_t axis = rank - 1;
    while (axis-- > 0) {
      ++index[axis];
      for (std::size_t k = 0; k < N; ++k) base[k] += strides[k][axis];
      if (index[axis] < shape[axis]) break;
      for (std::size_t k = 0; k < N; ++k) base[k] -= strides[k][axis] * shape[axis];
      index[axis] = 0;
    }
    if (axis == SIZE_MAX) return;
  }
}

}  // namespace rtmot::detector::xnnpack::tail
