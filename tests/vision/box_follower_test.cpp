// The box follower (vision/box_follower.hpp): on the demo video's people (PETS09-S2L1's ground
// truth on vtest.avi's frames) followed boxes end nearer the truth a second later than boxes left
// where they were; on generated images it finds a known sub-pixel shift, and it refuses what it
// cannot follow (a flat image, empty, non-finite or off-frame boxes) by leaving the box unchanged.
#include "vision/box_follower.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <set>
#include <stdexcept>
#include <vector>

#include "s2l1_ground_truth.hpp"
#include "tracker/box_geometry.hpp"
#include "vtest_frames.hpp"

namespace rtmot::vision {
namespace {

constexpr float kHalf = 0.5F;  // the thumbnails: half the frame's size, as the pipeline makes them

cv::Mat gray_thumbnail(const cv::Mat& frame) {
  cv::Mat small;
  cv::resize(frame, small, cv::Size(), kHalf, kHalf, cv::INTER_AREA);
  if (small.channels() == 1) return small;
  cv::Mat gray;
  cv::cvtColor(small, gray, cv::COLOR_BGR2GRAY);
  return gray;
}

// A person worth following: tall enough to have points, wholly in the frame.
bool followable(const tracker::Box& box, const cv::Size& frame) {
  return box.h >= 40.F && box.x >= 0.F && box.y >= 0.F && box.x + box.w <= frame.width &&
         box.y + box.h <= frame.height;
}

TEST(BoxFollower, PeopleFollowedThroughASecondEndNearerTheirTruthThanBoxesLeftBehind) {
  // One second of the 7 fps video from each of these frames, spread over the sequence.
  constexpr int kSteps = 7;
  const std::vector<int> starts = {40, 140, 240, 340, 440, 540, 640, 740};
  std::set<int> numbers;
  for (const int start : starts)
    for (int f = start; f <= start + kSteps; ++f) numbers.insert(f);
  const auto frames = test::vtest_frames(numbers);
  ASSERT_EQ(frames.size(), numbers.size());
  const auto truth = test::s2l1_ground_truth(numbers);

  BoxFollower follower;
  double followed_iou = 0.0;
  double static_iou = 0.0;
  int people = 0;
  int followed_steps = 0;
  int steps = 0;
  for (const int start : starts) {
    const cv::Size size = frames.at(start).size();
    std::vector<int> ids;
    std::vector<tracker::Box> boxes;
    for (const auto& [id, box] : truth.at(start)) {
      if (!followable(box, size) || truth.at(start + kSteps).count(id) == 0) continue;
      ids.push_back(id);
      boxes.push_back(box);
    }
    const std::vector<tracker::Box> at_start = boxes;
    follower.reset();
    follower.push(gray_thumbnail(frames.at(start)), kHalf);
    std::vector<FollowedBox> out;
    for (int f = start + 1; f <= start + kSteps; ++f) {
      follower.push(gray_thumbnail(frames.at(f)), kHalf);
      ASSERT_TRUE(follower.ready());
      follower.follow(boxes, out);
      ASSERT_EQ(out.size(), boxes.size());
      for (std::size_t i = 0; i < boxes.size(); ++i) {
        // Unfollowed boxes stay where they were (the tracker would predict them instead).
        boxes[i] = out[i].box;
        followed_steps += out[i].followed ? 1 : 0;
        ++steps;
      }
    }
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      const tracker::Box& end = truth.at(start + kSteps).at(ids[i]);
      followed_iou += tracker::iou(boxes[i], end);
      static_iou += tracker::iou(at_start[i], end);
      ++people;
    }
  }
  ASSERT_GT(people, 30);
  followed_iou /= people;
  static_iou /= people;
  const double followed_share = static_cast<double>(followed_steps) / steps;
  std::cout << people << " people followed through " << kSteps << " frames: mean IoU with the "
            << "truth " << followed_iou << " followed, " << static_iou << " left behind; "
            << followed_share << " of the steps followed\n";
  // Measured (default config, GStreamer's decoding): 48 people, IoU 0.62 followed against 0.24
  // left behind, 0.95 of the steps followed. Margins for other decoders and CPUs.
  EXPECT_GT(followed_iou, static_iou + 0.25);
  EXPECT_GT(followed_iou, 0.5);
  EXPECT_GT(followed_share, 0.85);
}

// A frame of flat gray with a smooth random texture over `patch`, shifted by (dx, dy) frame pixels;
// another `seed`, another texture.
cv::Mat textured_frame(const cv::Size& size, const cv::Rect& patch, float dx, float dy,
                       std::uint64_t seed = 29) {
  cv::Mat texture(patch.size(), CV_8UC1);
  cv::RNG rng(seed);  // the same texture for the same seed
  rng.fill(texture, cv::RNG::UNIFORM, 0, 256);
  cv::GaussianBlur(texture, texture, cv::Size(0, 0), 2.0);
  cv::Mat frame(size, CV_8UC1, cv::Scalar(128));
  texture.copyTo(frame(patch));
  const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, dx, 0, 1, dy);
  cv::Mat shifted;
  cv::warpAffine(frame, shifted, shift, size, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  return shifted;
}

TEST(BoxFollower, FindsAKnownSubPixelShiftOfATexturedPatch) {
  const cv::Size size(640, 480);
  const cv::Rect patch(200, 100, 120, 240);
  const tracker::Box box{200.F, 100.F, 120.F, 240.F};
  for (const auto& [dx, dy] :
       {std::pair{3.4F, -2.2F}, std::pair{-7.7F, 5.3F}, std::pair{0.F, 0.F}}) {
    BoxFollower follower;
    follower.push(gray_thumbnail(textured_frame(size, patch, 0.F, 0.F)), kHalf);
    follower.push(gray_thumbnail(textured_frame(size, patch, dx, dy)), kHalf);
    std::vector<FollowedBox> out;
    follower.follow({box}, out);
    ASSERT_EQ(out.size(), 1U);
    ASSERT_TRUE(out[0].followed) << "shift " << dx << ", " << dy;
    std::cout << "shift (" << dx << ", " << dy << "): found (" << out[0].box.x - box.x << ", "
              << out[0].box.y - box.y << "), size x" << out[0].box.w / box.w << ", confidence "
              << out[0].confidence << "\n";
    // Measured: within 0.05 px of the shift.
    EXPECT_NEAR(out[0].box.center_x() - box.center_x(), dx, 0.5F);
    EXPECT_NEAR(out[0].box.center_y() - box.center_y(), dy, 0.5F);
    EXPECT_NEAR(out[0].box.w / box.w, 1.F, 0.02F);
    EXPECT_NEAR(out[0].box.h / box.h, 1.F, 0.02F);
    EXPECT_GT(out[0].confidence, 0.9F);
  }
}

TEST(BoxFollower, FindsTheShiftWithWindowsOfOtherSides) {
  // The default window (9) runs loops compiled for its side; any other side the same loops with
  // the side known at run time (vision/lucas_kanade.cpp). Both must find the shift; an even side
  // is the odd one above it.
  const cv::Size size(640, 480);
  const cv::Rect patch(200, 100, 120, 240);
  const tracker::Box box{200.F, 100.F, 120.F, 240.F};
  const float dx = 3.4F;
  const float dy = -2.2F;
  for (const int window : {5, 8, 13}) {
    BoxFollowerConfig config;
    config.window = window;
    BoxFollower follower(config);
    follower.push(gray_thumbnail(textured_frame(size, patch, 0.F, 0.F)), kHalf);
    follower.push(gray_thumbnail(textured_frame(size, patch, dx, dy)), kHalf);
    std::vector<FollowedBox> out;
    follower.follow({box}, out);
    ASSERT_EQ(out.size(), 1U);
    ASSERT_TRUE(out[0].followed) << "window " << window;
    std::cout << "window " << window << ": found (" << out[0].box.center_x() - box.center_x()
              << ", " << out[0].box.center_y() - box.center_y() << "), confidence "
              << out[0].confidence << "\n";
    EXPECT_NEAR(out[0].box.center_x() - box.center_x(), dx, 0.5F) << "window " << window;
    EXPECT_NEAR(out[0].box.center_y() - box.center_y(), dy, 0.5F) << "window " << window;
    EXPECT_GT(out[0].confidence, 0.9F) << "window " << window;
  }
}

TEST(BoxFollower, FollowsAPatchThatGrowsAsItComesNearer) {
  const cv::Size size(640, 480);
  const cv::Rect patch(200, 100, 120, 240);
  cv::Mat before = textured_frame(size, patch, 0.F, 0.F);
  // Grown by 10 % around the patch's centre.
  const cv::Point2f centre(260.F, 220.F);
  const cv::Mat grow = cv::getRotationMatrix2D(centre, 0.0, 1.1);
  cv::Mat after;
  cv::warpAffine(before, after, grow, size, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  BoxFollower follower;
  follower.push(gray_thumbnail(before), kHalf);
  follower.push(gray_thumbnail(after), kHalf);
  std::vector<FollowedBox> out;
  const tracker::Box box{200.F, 100.F, 120.F, 240.F};
  follower.follow({box}, out);
  ASSERT_TRUE(out[0].followed);
  std::cout << "grown x1.1: size x" << out[0].box.w / box.w << ", centre moved ("
            << out[0].box.center_x() - box.center_x() << ", "
            << out[0].box.center_y() - box.center_y() << ")\n";
  EXPECT_NEAR(out[0].box.w / box.w, 1.1F, 0.03F);
  EXPECT_NEAR(out[0].box.center_x(), box.center_x(), 1.F);
  EXPECT_NEAR(out[0].box.center_y(), box.center_y(), 1.F);
}

TEST(BoxFollower, WhatIsNoLongerThereIsNotFollowed) {
  // The box's pixels replaced by others (a cut, an occluder): a quarter of the points come back
  // to where they started by chance, but they go different ways. Measured: confidence 0.125
  // (the two points nearest the median motion agree with it, as any two would).
  const cv::Size size(640, 480);
  const cv::Rect patch(200, 100, 120, 240);
  BoxFollower follower;
  follower.push(gray_thumbnail(textured_frame(size, patch, 0.F, 0.F, 29)), kHalf);
  follower.push(gray_thumbnail(textured_frame(size, patch, 0.F, 0.F, 30)), kHalf);
  const tracker::Box box{200.F, 100.F, 120.F, 240.F};
  std::vector<FollowedBox> out;
  follower.follow({box}, out);
  ASSERT_EQ(out.size(), 1U);
  std::cout << "another texture: confidence " << out[0].confidence << "\n";
  EXPECT_FALSE(out[0].followed);
  EXPECT_LT(out[0].confidence, 0.2F);
  EXPECT_EQ(out[0].box.x, box.x);
  EXPECT_EQ(out[0].box.y, box.y);
}

TEST(BoxFollower, AFlatImageHasNothingToFollow) {
  const cv::Mat flat(288, 384, CV_8UC1, cv::Scalar(128));
  BoxFollower follower;
  follower.push(flat, kHalf);
  follower.push(flat, kHalf);
  const tracker::Box box{300.F, 200.F, 60.F, 150.F};
  std::vector<FollowedBox> out;
  follower.follow({box}, out);
  ASSERT_EQ(out.size(), 1U);
  EXPECT_FALSE(out[0].followed);
  EXPECT_EQ(out[0].confidence, 0.F);
  EXPECT_EQ(out[0].box.x, box.x);
  EXPECT_EQ(out[0].box.y, box.y);
  EXPECT_EQ(out[0].box.w, box.w);
  EXPECT_EQ(out[0].box.h, box.h);
}

TEST(BoxFollower, BoxesItCannotFollowComeBackUnchangedBesideOnesItCan) {
  const cv::Size size(640, 480);
  const cv::Rect patch(0, 100, 200, 240);  // touches the frame's left edge
  BoxFollower follower;
  follower.push(gray_thumbnail(textured_frame(size, patch, 0.F, 0.F)), kHalf);
  follower.push(gray_thumbnail(textured_frame(size, patch, 4.F, 2.F)), kHalf);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const std::vector<tracker::Box> boxes = {
      {-60.F, 100.F, 120.F, 240.F},   // half outside the frame: its visible half is followed
      {20.F, 120.F, 0.F, 100.F},      // zero width
      {20.F, 120.F, 50.F, -10.F},     // negative height
      {nan, 120.F, 50.F, 100.F},      // NaN
      {20.F, 120.F, inf, 100.F},      // infinite
      {700.F, 100.F, 60.F, 150.F},    // wholly outside
      {-500.F, -500.F, 60.F, 150.F},  // wholly outside, the other way
      {50.F, 150.F, 1.F, 1.F},        // one pixel: a point or two in the thumbnail
  };
  std::vector<FollowedBox> out;
  follower.follow(boxes, out);
  ASSERT_EQ(out.size(), boxes.size());
  EXPECT_TRUE(out[0].followed);
  EXPECT_NEAR(out[0].box.center_x() - boxes[0].center_x(), 4.F, 0.5F);
  EXPECT_NEAR(out[0].box.center_y() - boxes[0].center_y(), 2.F, 0.5F);
  for (std::size_t i = 1; i < boxes.size(); ++i) {
    EXPECT_FALSE(out[i].followed) << "box " << i;
    EXPECT_EQ(out[i].confidence, 0.F) << "box " << i;
    // Bitwise: a NaN stays the NaN it was.
    EXPECT_EQ(std::memcmp(&out[i].box, &boxes[i], sizeof(tracker::Box)), 0) << "box " << i;
  }
}

TEST(BoxFollower, IsReadyOnlyWithTwoFramesOfOneSizeSinceTheLastReset) {
  const cv::Mat frame(288, 384, CV_8UC1, cv::Scalar(90));
  BoxFollower follower;
  EXPECT_FALSE(follower.ready());
  follower.push(frame, kHalf);
  EXPECT_FALSE(follower.ready());
  follower.push(frame, kHalf);
  EXPECT_TRUE(follower.ready());
  follower.reset();
  EXPECT_FALSE(follower.ready());
  const tracker::Box box{10.F, 10.F, 50.F, 100.F};
  std::vector<FollowedBox> out;
  follower.follow({box, box}, out);
  ASSERT_EQ(out.size(), 2U);
  EXPECT_FALSE(out[0].followed);
  EXPECT_EQ(out[1].box.x, box.x);
  follower.push(frame, kHalf);
  EXPECT_FALSE(follower.ready());
  follower.push(frame, kHalf);
  EXPECT_TRUE(follower.ready());
  // Another size, or another scale, is another camera set-up: nothing to follow across.
  follower.push(cv::Mat(144, 192, CV_8UC1, cv::Scalar(90)), kHalf);
  EXPECT_FALSE(follower.ready());
  follower.push(cv::Mat(144, 192, CV_8UC1, cv::Scalar(90)), 0.25F);
  EXPECT_FALSE(follower.ready());
}

TEST(BoxFollower, RefusesWhatIsNotAGrayThumbnail) {
  BoxFollower follower;
  EXPECT_THROW(follower.push(cv::Mat(), kHalf), std::invalid_argument);
  EXPECT_THROW(follower.push(cv::Mat(10, 10, CV_8UC3), kHalf), std::invalid_argument);
  EXPECT_THROW(follower.push(cv::Mat(10, 10, CV_8UC1), 0.F), std::invalid_argument);
  EXPECT_THROW(follower.push(cv::Mat(10, 10, CV_8UC1), std::nanf("")), std::invalid_argument);
  EXPECT_THROW(BoxFollower(BoxFollowerConfig{1}), std::invalid_argument);
  EXPECT_FALSE(follower.ready());
}

}  // namespace
}  // namespace rtmot::vision
