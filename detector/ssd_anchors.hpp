#pragma once
// The SSD's anchors, as scripts/tfjs_to_onnx.py writes them beside the model (see docs/model.md).
#include <filesystem>
#include <vector>

namespace rtmot::detector {

/// One anchor in normalised image coordinates (0..1), centre and size.
struct Anchor {
  float y_center{0.F};
  float x_center{0.F};
  float height{0.F};
  float width{0.F};
};

/// Reads an anchors CSV: '#' comment lines, then `ycenter,xcenter,height,width` per line.
/// Throws rtmot::InputError (ExitCode::bad_model) naming file and line when it is missing or
/// malformed.
std::vector<Anchor> read_anchors(const std::filesystem::path& path);

}  // namespace rtmot::detector
