#pragma once
// The int8 engine's calibration (backend xnnpack-int8, docs/cpu-detector.md "INT8"): the range
// every activation tensor of one model took in fp32 over sample frames, as a small text file that
// names the model's SHA-256 it belongs to. scripts/calibrate_int8.sh writes it (`rtmot model
// calibrate`); the detector reads it and refuses one that is damaged or made for another model.
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>

namespace rtmot::detector {

struct ActivationRange {
  float min{0.F};
  float max{0.F};
};

struct ActivationRanges {
  std::string model_sha256;  // lower-case hex of the model file the ranges were measured on
  int frames{0};             // how many sample frames were run
  std::map<std::string, ActivationRange> tensors;  // by ONNX tensor name; the input's included
};

/// At most this many bytes: one line per tensor of an SSD is a few KB.
constexpr std::uint64_t kMaxActivationRangesBytes = 4ULL << 20;

/// The ranges file that belongs to a model when none is named: committed beside the configs,
/// configs/int8/<model file name without .onnx>.ranges (relative as the model's default path is).
std::filesystem::path default_activation_ranges_path(const std::filesystem::path& model_path);

/// Parses the file. Throws rtmot::InputError (ExitCode::bad_model) naming the file, the line and
/// the field: missing or unreadable file, an unknown key, a malformed or non-finite number, min
/// above max, a tensor listed twice, no model_sha256, no tensors.
ActivationRanges read_activation_ranges(const std::filesystem::path& path);

/// Throws rtmot::InputError (ExitCode::bad_model) naming `path` and its model_sha256 field when the
/// ranges were measured on another model than `model_sha256`.
void check_ranges_belong_to(const ActivationRanges& ranges, const std::filesystem::path& path,
                            const std::string& model_sha256);

/// The file's text (read_activation_ranges reads it back exactly: floats to 9 significant digits).
std::string activation_ranges_text(const ActivationRanges& ranges);

}  // namespace rtmot::detector
