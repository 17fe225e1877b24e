#pragma once
// Intersection over union in double precision, as the devkit computes it (no +1 pixel). The
// product's IoU is tracker::iou (tracker/box_geometry.hpp, float, as SORT); the scorer keeps its
// own because it must reproduce the devkit's numbers to the printed digit, and a float IoU moves
// pairs that sit exactly at the 0.5 match threshold.
#include <algorithm>

#include "tracker/box.hpp"

namespace rtmot::mot {

inline double box_iou(const tracker::Box& a, const tracker::Box& b) {
  const double ax = a.x, ay = a.y, aw = a.w, ah = a.h;
  const double bx = b.x, by = b.y, bw = b.w, bh = b.h;
  const double overlap_x = std::max(0.0, std::min(ax + aw, bx + bw) - std::max(ax, bx));
  const double overlap_y = std::max(0.0, std::min(ay + ah, by + bh) - std::max(ay, by));
  const double intersection = overlap_x * overlap_y;
  const double union_area = aw * ah + bw * bh - intersection;
  return union_area > 0.0 ? intersection / union_area : 0.0;
}

}  // namespace rtmot::mot
