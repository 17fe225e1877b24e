#pragma once
// How far two boxes of one object are apart: the largest move of any of their four edges, in
// pixels. The detector tests compare engines, layouts and references by it.
#include <algorithm>
#include <cmath>

#include "tracker/box.hpp"

namespace rtmot::test {

inline float box_deviation(const tracker::Box& a, const tracker::Box& b) {
  return std::max({std::abs(a.x - b.x), std::abs(a.y - b.y), std::abs(a.x + a.w - b.x - b.w),
                   std::abs(a.y + a.h - b.y - b.h)});
}

}  // namespace rtmot::test
