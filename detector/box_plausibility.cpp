#include "detector/box_plausibility.hpp"

#include "detector/ssd_defaults.hpp"

namespace rtmot::detector {
namespace {
// People: MOTChallenge 2015's ground truth (39,905 boxes, 11 scenes) is at most 1.10 wide for 1
// tall (a cyclist, KITTI-13), 0.55 at its 99th percentile. The SSD's boxes matched to people
// (IoU >= 0.5) on PETS09-S2L1 and ADL-Rundle-6 (3,530 and 968 of them) are at most 0.75 and 0.77;
// its 178 boxes on S2L1 wider than 1.25 are all false (rows of people or half the street as one
// "person"). 1.25 keeps the widest annotated person with a margin (docs/tiling.md).
constexpr float kMaxPersonAspect = 1.25F;
}  // namespace

float max_plausible_aspect(int class_id) {
  if (class_id == kPersonClassId) return kMaxPersonAspect;
  return std::numeric_limits<float>::infinity();
}

}  // namespace rtmot::detector
