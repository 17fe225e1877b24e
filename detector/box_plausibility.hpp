#pragma once
// Shapes an object of a class does not have: the SSD now and then calls half a street scene a
// "person" (a box five times wider than tall). Such a box is dropped before NMS, so it can neither
// become a track nor suppress a real person's box (docs/tiling.md, "Boxes a person would trust").
#include <limits>

namespace rtmot::detector {

/// The widest box (width / height, in frame pixels) an object of COCO class `class_id` is kept at;
/// infinity for the classes nothing was measured on.
float max_plausible_aspect(int class_id);

/// Whether a `width` x `height` pixel box of `class_id` has a shape the class has.
inline bool plausible_shape(int class_id, float width, float height) {
  return width <= max_plausible_aspect(class_id) * height;
}

}  // namespace rtmot::detector
