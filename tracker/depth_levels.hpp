#pragma once
// SparseTrack's pseudo-depth (Liu et al. 2023): on a ground seen from above or level, a person
// whose feet are lower in the image stands nearer the camera and hides those behind. The levels
// are equal slices of one frame's range of box bottoms, level 0 the nearest.
#include <algorithm>
#include <cmath>

#include "tracker/box.hpp"

namespace rtmot::tracker {

class DepthLevels {
 public:
  /// `count` levels over the bottoms [lowest_bottom, highest_bottom] (image y grows downwards).
  DepthLevels(int count, float lowest_bottom, float highest_bottom)
      : count_(std::max(count, 1)), nearest_(highest_bottom), span_(highest_bottom - lowest_bottom) {}

  int count() const { return count_; }

  /// 0 for the nearest boxes (bottom at the range's lowest point in the image), count() - 1 for
  /// the furthest; a range without extent is one level.
  int level(const Box& box) const {
    if (!(span_ > 0.F)) return 0;
    const float from_nearest = (nearest_ - (box.y + box.h)) / span_;
    const int slice = static_cast<int>(std::floor(from_nearest * static_cast<float>(count_)));
    return std::clamp(slice, 0, count_ - 1);
  }

 private:
  int count_;
  float nearest_;
  float span_;
};

}  // namespace rtmot::tracker
