#pragma once
// `rtmot model check`: what a model file holds as the detector sees it, and which engines of this
// build and machine run it, before a run depends on it. The contract it checks is the one
// SsdDetector runs (docs/model.md, "The model contract"); every mismatch is named with the field.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "detector/model_description.hpp"

namespace rtmot::detector {

struct ModelCheckConfig {
  std::filesystem::path model_path;
  /// Empty: default_anchors_path(model_path), as the detector reads it.
  std::filesystem::path anchors_path;
  /// The int8 engine's activation ranges; empty: default_activation_ranges_path(model_path), as
  /// the detector reads them.
  std::filesystem::path int8_ranges;
};

struct NamedShape {
  std::string name;
  std::vector<int> shape;
};

struct EngineCheck {
  std::string engine;  // "cpu" (OpenCV), "xnnpack", "cuda"
  bool runs{false};
  std::string detail;  // the forward pass's median time, or why the engine cannot run the model
};

struct ModelCheck {
  std::filesystem::path model;
  /// The description beside the model (model_description.hpp; file empty: none), as read.
  ModelDescription description;
  std::string labels;  // where the class names come from, and how many
  std::uintmax_t model_bytes{0};
  std::string checksums;               // what the model's .sha256 said
  std::vector<NamedShape> outputs;     // as OpenCV computes them for one image
  bool batch_dimension{false};         // two images in one pass give two rows
  int anchors_in_model{0};             // rows of the outputs
  int class_columns{0};                // columns of the class output, background first
  int label_columns{0};                // lines of the labels (COCO's table: 91)
  std::filesystem::path anchors_file;  // layout deltas only
  int anchors_in_file{0};
  std::vector<EngineCheck> engines;
  /// backend xnnpack-int8 (never chosen by auto, so not among `engines`): whether it runs the
  /// model with `int8_ranges`, or why not.
  std::filesystem::path int8_ranges;
  EngineCheck int8;
  /// Each names the field that does not fit the contract; empty when `rtmot run` can use the model.
  std::vector<std::string> problems;

  bool usable() const;
};

/// Loads and runs the model on every engine this build has. Throws rtmot::InputError
/// (ExitCode::bad_model) naming the file when the model cannot be opened at all (missing, a
/// folder, too large) or its description is not valid (file, line and field); everything found
/// after that is reported in the result.
ModelCheck check_model(const ModelCheckConfig& config);

/// The report `rtmot model check` prints: one fact per line.
std::string format_model_check(const ModelCheck& check);

}  // namespace rtmot::detector
