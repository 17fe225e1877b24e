#pragma once
// The model contract SsdDetector runs (docs/model.md, "The model contract"), defined once for the
// detector, its XNNPACK engine and `rtmot model check`.
#include "detector/coco_labels.hpp"

namespace rtmot::detector {

/// The network's input: N x 3 x this x this floats, RGB planes.
constexpr int kModelInputSize = 300;
/// The square inputs a model's description may give. Below 64 px an SSD's coarsest feature maps
/// vanish; above 1024 px one image's activations outgrow a board's cache many times over, and no
/// SSD-family detector of this kind is trained that large.
constexpr int kMinModelInputSize = 64;
constexpr int kMaxModelInputSize = 1024;
/// The ONNX metadata key (ModelProto.metadata_props) whose value is a model's description, the
/// same YAML as `<model stem>.model.yaml`, for a model that carries it inside.
inline constexpr const char* kDescriptionMetadataKey = "rtmot.model";
/// [0, 255] -> [-1, 1]: (value - 127.5) / 127.5, as the TF graph's Preprocessor.
constexpr double kModelPixelScale = 1.0 / 127.5;
/// [N, anchors, 4] box deltas (ty, tx, th, tw) against the anchors file's rows.
inline constexpr const char* kBoxOutputName = "box_encodings";
/// [N, anchors, columns] class logits, column 0 the background, column k COCO id k.
inline constexpr const char* kClassOutputName = "class_logits";
/// Columns of the class output: COCO's ids 0..90.
constexpr int kModelClassColumns = kCocoMaxClassId + 1;

}  // namespace rtmot::detector
