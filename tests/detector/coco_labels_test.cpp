#include "detector/coco_labels.hpp"

#include <gtest/gtest.h>

namespace rtmot::detector {
namespace {

TEST(CocoLabels, UsesThe91IdMapWithItsGaps) {
  EXPECT_EQ(coco_label(1), "person");
  EXPECT_EQ(coco_label(3), "car");
  EXPECT_EQ(coco_label(12), "");  // reserved id: no annotations
  EXPECT_EQ(coco_label(13), "stop sign");
  EXPECT_EQ(coco_label(90), "toothbrush");
  EXPECT_EQ(coco_label(0), "");
  EXPECT_EQ(coco_label(91), "");
  int used = 0;
  for (int id = 1; id <= kCocoMaxClassId; ++id) used += coco_label(id).empty() ? 0 : 1;
  EXPECT_EQ(used, 80);  // COCO's 80 detection classes
}

TEST(CocoLabels, LooksIdsUpByLabel) {
  EXPECT_EQ(coco_class_id("person"), 1);
  EXPECT_EQ(coco_class_id("bus"), 6);
  EXPECT_EQ(coco_class_id("toothbrush"), 90);
  EXPECT_EQ(coco_class_id("unicorn"), -1);
  EXPECT_EQ(coco_class_id(""), -1);
}

}  // namespace
}  // namespace rtmot::detector
