#pragma once
// What the XNNPACK engine (xnnpack_network.hpp) reads from the ONNX model before it builds
// anything from it: the bounds on every size the file declares, sizes that saturate instead of
// wrapping, and nodes' attributes. Internal to detector/.
#include <onnx/onnx_pb.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace rtmot::detector::xnnpack {

// Every size the file declares (tensor dimensions, kernel sizes, pads, strides, dilations, groups)
// is bounded before anything is computed or allocated from it, and so is every tensor the builder
// defines: a damaged or hostile model fails naming its node or tensor (bad_model), never with
// std::bad_alloc or an overflow (issue 32: huge pads exited 1). Far above what an SSD needs (its
// largest dimension is 1280 channels, its largest feature map 2.2 M floats an image).
constexpr std::int64_t kMaxDeclaredSize = std::int64_t{1} << 16;
constexpr std::size_t kMaxTensorFloatsPerImage = std::size_t{1} << 26;  // 256 MB

// Saturates at SIZE_MAX instead of wrapping, so that a product compared with a bound or a count
// stays honest.
std::size_t product(const std::vector<std::size_t>& dims, std::size_t from = 0);

bool declared_size_ok(std::int64_t value, std::int64_t least);

std::string shape_text(const std::vector<std::size_t>& dims);

const onnx::AttributeProto* attribute(const onnx::NodeProto& node, const char* name);

std::int64_t int_attribute(const onnx::NodeProto& node, const char* name, std::int64_t fallback);

std::vector<std::int64_t> ints_attribute(const onnx::NodeProto& node, const char* name,
                                         std::vector<std::int64_t> fallback);

}  // namespace rtmot::detector::xnnpack
