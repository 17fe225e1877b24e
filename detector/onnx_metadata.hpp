#pragma once
// One entry of an ONNX model's metadata (ModelProto.metadata_props), read without the ONNX
// library: a model may carry its description inside (docs/model.md, "The model contract").
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace rtmot::detector {

/// The value of metadata entry `key` of the ONNX file `path`, or nothing when the file has no
/// such entry, is not a regular readable file (a FIFO is never opened for reading: it would block)
/// or is not a readable ONNX model (whoever loads the network reports those). Throws
/// rtmot::InputError (ExitCode::bad_model) naming the file and the key when the value is longer
/// than `max_bytes`.
std::optional<std::string> onnx_metadata_value(const std::filesystem::path& path,
                                               const std::string& key, std::uint64_t max_bytes);

}  // namespace rtmot::detector
