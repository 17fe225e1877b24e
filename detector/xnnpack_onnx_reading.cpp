#include "detector/xnnpack_onnx_reading.hpp"

#include <limits>

namespace rtmot::detector::xnnpack {

std::size_t product(const std::vector<std::size_t>& dims, std::size_t from) {
  std::size_t n = 1;
  for (std::size_t i = from; i < dims.size(); ++i) {
    if (dims[i] != 0 && n > std::numeric_limits<std::size_t>::max() / dims[i]) {
      return std::numeric_limits<std::size_t>::max();
    }
    n *= dims[i];
  }
  return n;
}

bool declared_size_ok(std::int64_t value, std::int64_t least) {
  return value >= least && value <= kMaxDeclaredSize;
}

std::string shape_text(const std::vector<std::size_t>& dims) {
  std::string text;
  for (std::size_t i = 0; i < dims.size(); ++i) text += (i ? "x" : "") + std::to_string(dims[i]);
  return text;
}

const onnx::AttributeProto* attribute(const onnx::NodeProto& node, const char* name) {
  for (const auto& a : node.attribute()) {
    if (a.name() == name) return &a;
  }
  return nullptr;
}

std::int64_t int_attribute(const onnx::NodeProto& node, const char* name, std::int64_t fallback) {
  const auto* a = attribute(node, name);
  return a ? a->i() : fallback;
}

std::vector<std::int64_t> ints_attribute(const onnx::NodeProto& node, const char* name,
                                         std::vector<std::int64_t> fallback) {
  const auto* a = attribute(node, name);
  if (!a) return fallback;
  return {a->ints().begin(), a->ints().end()};
}

}  // namespace rtmot::detector::xnnpack
