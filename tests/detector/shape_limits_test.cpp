// The SSD's shape limits (detector/box_plausibility.hpp) on the demo video's reference frames: with
// them the detector reports exactly what it reports without them, less the boxes of shapes their
// class does not have, plus only boxes that such a box had suppressed in NMS. And the "person"
// across half of frame 101 is gone.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <vector>

#include "detector/box_plausibility.hpp"
#include "detector/ssd_detector.hpp"
#include "shared_data.hpp"
#include "tracker/box_geometry.hpp"
#include "vtest_frames.hpp"

namespace rtmot::detector {
namespace {

bool same(const tracker::Detection& a, const tracker::Detection& b) {
  return a.class_id == b.class_id && std::abs(a.score - b.score) < 1e-6F &&
         tracker::iou(a.box, b.box) > 0.999F;
}

TEST(ShapeLimits, DropExactlyTheImplausibleBoxesOfTheDemoVideo) {
  SsdConfig config;
  config.model_path = test::source_path("models/ssdlite_mobilenet_v2_coco.onnx");
  config.backend = BackendRequest::cpu;
  config.classes = {};  // every class: the limits are per class
  SsdDetector limited(config);
  config.plausible_shapes = false;
  SsdDetector unlimited(config);
  std::set<int> numbers;
  for (int frame = 1; frame <= 701; frame += 100) numbers.insert(frame);  // 101 among them
  const auto frames = test::vtest_frames(numbers);
  ASSERT_EQ(frames.size(), numbers.size());
  int dropped = 0;
  int widest_person_frame_101 = 0;
  for (const auto& [number, image] : frames) {
    std::vector<tracker::Detection> with;
    std::vector<tracker::Detection> without;
    limited.detect(image, number, with);
    unlimited.detect(image, number, without);
    std::vector<tracker::Detection> implausible;
    for (const auto& d : without) {
      const bool kept =
          std::any_of(with.begin(), with.end(), [&](const auto& w) { return same(w, d); });
      // Boxes are clipped to the frame after the check, so a clipped box may look narrower: the
      // ones dropped must be implausible by a margin, the ones kept must not be far past the limit.
      if (!kept) {
        EXPECT_GT(d.box.w, max_plausible_aspect(d.class_id) * d.box.h * 0.95F)
            << "frame " << number << ": a plausible box of class " << d.class_id << " was dropped";
        implausible.push_back(d);
        ++dropped;
      }
    }
    for (const auto& w : with) {
      EXPECT_LE(w.box.w, max_plausible_aspect(w.class_id) * w.box.h * 1.05F) << "frame " << number;
      if (w.class_id == kPersonClassId && number == 101) {
        widest_person_frame_101 = std::max(widest_person_frame_101, static_cast<int>(w.box.w));
      }
      const bool was_there =
          std::any_of(without.begin(), without.end(), [&](const auto& d) { return same(w, d); });
      if (was_there) continue;
      // New only because an implausible box of its class no longer suppresses it in NMS.
      const bool was_suppressed =
          std::any_of(implausible.begin(), implausible.end(), [&](const auto& d) {
            return d.class_id == w.class_id && tracker::iou(d.box, w.box) > config.nms_iou;
          });
      EXPECT_TRUE(was_suppressed) << "frame " << number << ": a new box of class " << w.class_id;
    }
  }
  EXPECT_GT(dropped, 0) << "the demo video's wide 'people' were expected";
  // The frame 101: a "person" across x 20..680 of the 768-px frame. None wider than half
  // now.
  EXPECT_LT(widest_person_frame_101, 768 / 2);
  std::printf("%d implausible boxes dropped on %zu frames\n", dropped, frames.size());
}

}  // namespace
}  // namespace rtmot::detector
