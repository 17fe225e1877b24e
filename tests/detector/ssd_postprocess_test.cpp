// Box decoding and per-class NMS on hand-made network outputs whose right answers follow from the
// box coder's definition (TF OD API: centre offsets / 10, log sizes / 5, relative to the anchor).
// The geometry tests turn the shape limits off: their class-1 boxes are twice as wide as tall.
#include "detector/ssd_postprocess.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace rtmot::detector {
namespace {

constexpr int kClasses = 4;  // background + 3
constexpr int kWidth = 400;
constexpr int kHeight = 200;

float logit(float p) {
  return std::log(p / (1.F - p));
}

struct Outputs {
  explicit Outputs(std::size_t anchors)
      : boxes(anchors * 4, 0.F), logits(anchors * kClasses, -20.F) {}
  void score(std::size_t anchor, int class_id, float p) {
    logits[anchor * kClasses + static_cast<std::size_t>(class_id)] = logit(p);
  }
  std::vector<float> boxes;
  std::vector<float> logits;
};

std::vector<tracker::Detection> run(const std::vector<Anchor>& anchors, const Outputs& outputs,
                                    SsdPostprocessConfig config) {
  SsdPostprocessor post(anchors, kClasses, std::move(config));
  std::vector<tracker::Detection> out;
  post.run(outputs.boxes.data(), outputs.logits.data(), kWidth, kHeight, out);
  return out;
}

TEST(SsdPostprocess, ZeroCodesGiveTheAnchorInPixels) {
  const std::vector<Anchor> anchors{{0.5F, 0.25F, 0.2F, 0.1F}};
  Outputs outputs(1);
  outputs.score(0, 2, 0.8F);
  const auto out = run(anchors, outputs, {0.5F, 0.6F, 100, {}});
  ASSERT_EQ(out.size(), 1U);
  EXPECT_EQ(out[0].class_id, 2);
  EXPECT_NEAR(out[0].score, 0.8F, 1e-6);
  EXPECT_NEAR(out[0].box.x, (0.25F - 0.05F) * kWidth, 1e-3);
  EXPECT_NEAR(out[0].box.y, (0.5F - 0.1F) * kHeight, 1e-3);
  EXPECT_NEAR(out[0].box.w, 0.1F * kWidth, 1e-3);
  EXPECT_NEAR(out[0].box.h, 0.2F * kHeight, 1e-3);
}

TEST(SsdPostprocess, CodesShiftAndScaleRelativeToTheAnchor) {
  const std::vector<Anchor> anchors{{0.5F, 0.5F, 0.2F, 0.1F}};
  Outputs outputs(1);
  outputs.boxes = {10.F * 0.5F, -10.F * 1.F, 5.F * std::log(2.F), 0.F};  // ty, tx, th, tw
  outputs.score(0, 1, 0.9F);
  const auto out = run(anchors, outputs, {0.5F, 0.6F, 100, {}});
  ASSERT_EQ(out.size(), 1U);
  // centre y = 0.5 + 0.5 * 0.2 = 0.6, height 0.4; centre x = 0.5 - 1 * 0.1 = 0.4, width 0.1
  EXPECT_NEAR(out[0].box.center_y(), 0.6F * kHeight, 1e-3);
  EXPECT_NEAR(out[0].box.h, 0.4F * kHeight, 1e-3);
  EXPECT_NEAR(out[0].box.center_x(), 0.4F * kWidth, 1e-3);
  EXPECT_NEAR(out[0].box.w, 0.1F * kWidth, 1e-3);
}

TEST(SsdPostprocess, SuppressesPerClassAboveTheIouThreshold) {
  // Anchors 0 and 1 overlap with IoU 0.8, anchor 2 overlaps anchor 0 with IoU 1/3.
  const std::vector<Anchor> anchors{
      {0.5F, 0.5F, 0.2F, 0.2F}, {0.5F, 0.5F + 0.2F / 9.F, 0.2F, 0.2F}, {0.5F, 0.6F, 0.2F, 0.2F}};
  Outputs outputs(3);
  outputs.score(0, 1, 0.9F);
  outputs.score(1, 1, 0.8F);  // suppressed by anchor 0
  outputs.score(2, 1, 0.7F);  // kept: IoU 1/3
  outputs.score(1, 3, 0.6F);  // kept: another class
  const auto out = run(anchors, outputs, {0.5F, 0.6F, 100, {}, false});
  ASSERT_EQ(out.size(), 3U);
  EXPECT_NEAR(out[0].score, 0.9F, 1e-6);
  EXPECT_NEAR(out[1].score, 0.7F, 1e-6);
  EXPECT_EQ(out[2].class_id, 3);
}

TEST(SsdPostprocess, ThresholdClassFilterAndLimit) {
  const std::vector<Anchor> anchors{
      {0.1F, 0.1F, 0.1F, 0.1F}, {0.5F, 0.5F, 0.1F, 0.1F}, {0.9F, 0.9F, 0.1F, 0.1F}};
  Outputs outputs(3);
  outputs.score(0, 1, 0.5F);   // exactly the threshold: kept
  outputs.score(1, 1, 0.49F);  // below
  outputs.score(2, 2, 0.95F);  // other class
  auto out = run(anchors, outputs, {0.5F, 0.6F, 100, {1}, false});
  ASSERT_EQ(out.size(), 1U);
  EXPECT_EQ(out[0].class_id, 1);
  out = run(anchors, outputs, {0.5F, 0.6F, 1, {}, false});
  ASSERT_EQ(out.size(), 1U);
  EXPECT_EQ(out[0].class_id, 2);  // the best survives the limit
  EXPECT_THROW(run(anchors, outputs, {0.5F, 0.6F, 100, {kClasses}, false}), std::invalid_argument);
}

TEST(SsdPostprocess, ClipsToTheImage) {
  const std::vector<Anchor> anchors{{0.0F, 1.0F, 0.2F, 0.2F}, {-0.5F, 0.5F, 0.2F, 0.2F}};
  Outputs outputs(2);
  outputs.score(0, 1, 0.9F);
  outputs.score(1, 1, 0.9F);  // entirely above the image: dropped
  const auto out = run(anchors, outputs, {0.5F, 0.6F, 100, {}, false});
  ASSERT_EQ(out.size(), 1U);
  EXPECT_NEAR(out[0].box.x, 0.9F * kWidth, 1e-3);
  EXPECT_NEAR(out[0].box.y, 0.F, 1e-6);
  EXPECT_NEAR(out[0].box.x + out[0].box.w, kWidth, 1e-3);
  EXPECT_NEAR(out[0].box.h, 0.1F * kHeight, 1e-3);
}

TEST(SsdPostprocess, APersonWiderThanAPersonIsDroppedBeforeNms) {
  // In the 400 x 200 image: anchor 0 is 160 x 40 px (4:1), anchor 1 is 40 x 80 px inside it.
  const std::vector<Anchor> anchors{{0.5F, 0.5F, 0.2F, 0.4F}, {0.5F, 0.5F, 0.4F, 0.1F}};
  Outputs outputs(2);
  outputs.score(0, 1, 0.9F);  // a 'person' four times wider than tall
  outputs.score(1, 1, 0.6F);  // a person, overlapping it by IoU 0.2: NMS keeps both
  outputs.score(0, 3, 0.8F);  // a car of that shape is a car
  const auto out = run(anchors, outputs, {0.5F, 0.6F, 100, {}});
  ASSERT_EQ(out.size(), 2U);
  EXPECT_EQ(out[0].class_id, 3);
  EXPECT_EQ(out[1].class_id, 1);
  EXPECT_NEAR(out[1].box.w, 40.F, 1e-3);
  EXPECT_EQ(run(anchors, outputs, {0.5F, 0.6F, 100, {}, false}).size(), 3U);  // limits off
}

TEST(SsdPostprocess, AnImplausibleBoxSuppressesNothing) {
  // A 'person' of 160 x 80 px (2:1) scored 0.9 and a person of 80 x 80 px inside it scored 0.6,
  // IoU 0.5: at an NMS IoU of 0.4 the wide box would suppress the person; dropped first, it cannot.
  const std::vector<Anchor> anchors{{0.5F, 0.5F, 0.4F, 0.4F}, {0.5F, 0.5F, 0.4F, 0.2F}};
  Outputs outputs(2);
  outputs.score(0, 1, 0.9F);
  outputs.score(1, 1, 0.6F);
  const auto kept = run(anchors, outputs, {0.5F, 0.4F, 100, {}});
  ASSERT_EQ(kept.size(), 1U);
  EXPECT_NEAR(kept[0].box.w, 80.F, 1e-3);
  const auto without_limits = run(anchors, outputs, {0.5F, 0.4F, 100, {}, false});
  ASSERT_EQ(without_limits.size(), 1U);
  EXPECT_NEAR(without_limits[0].box.w, 160.F, 1e-3);
}

}  // namespace
}  // namespace rtmot::detector
