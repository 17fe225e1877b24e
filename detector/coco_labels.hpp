#pragma once
// COCO's 91-id label map (ids 1..90 with gaps, 0 = background), as the SSD's class outputs use it.
#include <string_view>

namespace rtmot::detector {

/// The label of a COCO class id ("person" for 1); empty for ids the map does not use.
std::string_view coco_label(int class_id);

/// The class id of a COCO label ("person" -> 1); -1 when no class has that label.
int coco_class_id(std::string_view label);

/// Largest id of the map (90); the model's class output has this + 1 columns.
constexpr int kCocoMaxClassId = 90;

}  // namespace rtmot::detector
