// The box follower's steady state allocates nothing of its own (vision/box_follower.hpp): once it
// has followed as many boxes as it gets, follow() allocates nothing, frame after frame of the demo
// video's people. This executable replaces the global operator new/delete to count allocations
// (tests/allocation_counter.hpp), so it is an executable of its own. push() is not counted:
// OpenCV's pyramid filters take their row scratch inside (box_follower.cpp says what).
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <set>
#include <vector>

#include "allocation_counter.hpp"
#include "s2l1_ground_truth.hpp"
#include "vision/box_follower.hpp"
#include "vtest_frames.hpp"

namespace rtmot::vision {
namespace {

TEST(BoxFollowerSteadyState, FollowAllocatesNothingOnceItHasSeenItsBoxes) {
  // Consecutive frames of the 7 fps video, its people's boxes at the first (the truth), each then
  // moved to where the follower says.
  constexpr int kFirst = 240;
  constexpr int kFrames = 12;
  std::set<int> numbers;
  for (int f = kFirst; f < kFirst + kFrames; ++f) numbers.insert(f);
  const auto frames = test::vtest_frames(numbers);
  ASSERT_EQ(frames.size(), numbers.size());
  const auto truth = test::s2l1_ground_truth({kFirst});
  ASSERT_EQ(truth.count(kFirst), 1U);
  std::vector<tracker::Box> boxes;
  for (const auto& [id, box] : truth.at(kFirst)) boxes.push_back(box);
  ASSERT_GT(boxes.size(), 3U);

  std::vector<cv::Mat> thumbnails;
  for (const auto& [number, frame] : frames) {
    cv::Mat small;
    cv::Mat gray;
    cv::resize(frame, small, cv::Size(), 0.5, 0.5, cv::INTER_AREA);
    cv::cvtColor(small, gray, cv::COLOR_BGR2GRAY);
    thumbnails.push_back(gray);
  }
  BoxFollower follower;
  std::vector<FollowedBox> out;
  int followed = 0;
  long allocations = 0;
  for (std::size_t f = 0; f < thumbnails.size(); ++f) {
    follower.push(thumbnails[f], 0.5F);
    if (f == 0) continue;
    // The first follow grows the buffers to these boxes; none after it may allocate.
    const test::CountingScope counting;
    follower.follow(boxes, out);
    if (f >= 2) allocations += counting.allocations();
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      boxes[i] = out[i].box;
      followed += out[i].followed ? 1 : 0;
    }
  }
  EXPECT_EQ(allocations, 0) << "allocations in follow() over " << thumbnails.size() - 2
                            << " frames";
  EXPECT_GT(followed, 0);  // it did follow people
}

}  // namespace
}  // namespace rtmot::vision
