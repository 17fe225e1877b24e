#pragma once
// How a model is fed and read, from the small file beside it (`<model stem>.model.yaml`), or the
// bundled model's contract when there is none (docs/model.md, "The model contract"). Two output
// layouts: the bundled model's box codes + class logits decoded against an anchors file, and the
// decoded boxes + scores of jetson-inference's pytorch-ssd export.
#include <filesystem>
#include <string>

#include "detector/model_contract.hpp"
#include "tracker/enum_names.hpp"

namespace rtmot::detector {

enum class OutputLayout {
  deltas,   // [N, A, 4] (ty, tx, th, tw) against the anchors + [N, A, C] logits (sigmoid)
  decoded,  // [N, A, 4] (x1, y1, x2, y2) in 0..1 + [N, A, C] probabilities
};
inline constexpr auto kOutputLayoutNames = tracker::make_enum_names<OutputLayout>(
    std::pair{OutputLayout::deltas, std::string_view("deltas")},
    std::pair{OutputLayout::decoded, std::string_view("decoded")});

enum class ColourOrder { rgb, bgr };
inline constexpr auto kColourOrderNames =
    tracker::make_enum_names<ColourOrder>(std::pair{ColourOrder::rgb, std::string_view("rgb")},
                                          std::pair{ColourOrder::bgr, std::string_view("bgr")});

struct ModelDescription {
  /// The file the description was read from: `<model stem>.model.yaml`, or the model itself when
  /// it carries its description in its metadata (inside_model); empty: the bundled contract.
  std::filesystem::path file;
  bool inside_model{false};
  OutputLayout layout{OutputLayout::deltas};
  int input_size{kModelInputSize};
  ColourOrder colour{ColourOrder::rgb};
  /// The network's input value = (pixel - mean) * scale, per channel alike.
  double mean{127.5};
  double scale{kModelPixelScale};
  std::string box_output{kBoxOutputName};
  std::string score_output{kClassOutputName};
  /// Empty: COCO's table. Relative paths in the file are relative to its folder.
  std::filesystem::path labels;
};

/// `<model stem>.model.yaml` beside the model.
std::filesystem::path description_path_of(const std::filesystem::path& model_path);

/// Where a description came from, for logs and `rtmot model check`.
std::string described_by(const ModelDescription& description);

/// The description beside the model; else the one inside it (ONNX metadata entry
/// kDescriptionMetadataKey, the same YAML); else the bundled contract. A file beside the model
/// wins, so that a user can correct a model's own description without rewriting the model. For
/// layout decoded the outputs default to jetson-inference's names, `boxes` and `scores`. Throws
/// rtmot::InputError (ExitCode::bad_model) naming the file (the model, for a description inside
/// it), line and field: not YAML, an unknown key, a value of the wrong type or out of range.
ModelDescription read_model_description(const std::filesystem::path& model_path);

}  // namespace rtmot::detector
