#pragma once
// Small box arithmetic shared by the affinities and the predictors.
#include <algorithm>
#include <cmath>

#include "tracker/box.hpp"

namespace rtmot::tracker {

/// Intersection over union, 0 for disjoint or degenerate boxes (as SORT's iou_batch, no +1 pixel).
inline float iou(const Box& a, const Box& b) {
  const float ix = std::max(0.F, std::min(a.x + a.w, b.x + b.w) - std::max(a.x, b.x));
  const float iy = std::max(0.F, std::min(a.y + a.h, b.y + b.h) - std::max(a.y, b.y));
  const float intersection = ix * iy;
  const float union_area = a.w * a.h + b.w * b.h - intersection;
  return union_area > 0.F ? intersection / union_area : 0.F;
}

/// The share of `box`'s area that `other` covers, in [0, 1].
inline float covered_share(const Box& box, const Box& other) {
  const float ix =
      std::max(0.F, std::min(box.x + box.w, other.x + other.w) - std::max(box.x, other.x));
  const float iy =
      std::max(0.F, std::min(box.y + box.h, other.y + other.h) - std::max(box.y, other.y));
  const float area = box.w * box.h;
  return area > 0.F ? ix * iy / area : 0.F;
}

/// The box grown about its centre by `margin` times its size on every side (C-BIoU's buffer).
inline Box enlarged(const Box& box, float margin) {
  return Box{box.x - margin * box.w, box.y - margin * box.h, box.w * (1.F + 2.F * margin),
             box.h * (1.F + 2.F * margin)};
}

/// Linear interpolation between two boxes, t in [0, 1].
inline Box interpolate(const Box& from, const Box& to, float t) {
  return Box{from.x + t * (to.x - from.x), from.y + t * (to.y - from.y),
             from.w + t * (to.w - from.w), from.h + t * (to.h - from.h)};
}

inline bool is_finite(const Box& box) {
  return std::isfinite(box.x) && std::isfinite(box.y) && std::isfinite(box.w) &&
         std::isfinite(box.h);
}

}  // namespace rtmot::tracker
