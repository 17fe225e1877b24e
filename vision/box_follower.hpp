#pragma once
// Following boxes through the frames the detector skipped: sparse optical flow (pyramidal
// Lucas-Kanade, vision/lucas_kanade.hpp) on a grid of points inside each box, from one gray
// thumbnail of the camera's frames to the next. A box moves by its points' median displacement
// and scales by the median ratio of their pairwise distances; points that do not come back to
// where they started when followed backwards (forward-backward error) are not trusted, so an
// occluder or a textureless box lowers the confidence instead of dragging the box. Used by the
// pipeline's track stage (docs/full-rate.md, "Observed boxes"); the tracker never sees an image.
#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "tracker/box.hpp"
#include "vision/lucas_kanade.hpp"

namespace rtmot::vision {

struct BoxFollowerConfig {
  // grid x grid points per box, over its inner part. The cost is per point (bench/vision_bench,
  // push + follow of 20 boxes, CPU time on this 2-core VM at load 1-5: 1.2-1.8 ms at 4, 1.0-1.2 ms
  // at 3; docs/full-rate.md, "Observed boxes"); on the first half of S2L1 (the
  // choosing protocol, docs/full-rate.md) 4 scored higher behind a slow detector (MOTA 28.2 against
  // 24.9 at 250 ms; IDF1 summed over 100/250/500 ms 100.0 against 97.8); 6 gave S2L1's people the
  // IoU that 4 did (0.63 vs 0.62 after 7 frames) at 2.6x the time.
  int grid = 4;
  int window = 9;               // Lucas-Kanade window side, thumbnail pixels
  int pyramid_levels = 2;       // above the thumbnail itself
  float max_round_trip = 1.0F;  // forward-backward error a trusted point may have, thumbnail px
  float min_trusted = 0.3F;     // share of points trusted and agreeing (confidence) to move it
};

/// Where one box went.
struct FollowedBox {
  tracker::Box box;       // frame pixels (the input box when not followed)
  float confidence{0.F};  // share of its points trusted and agreeing with its motion, 0..1
  bool followed{false};   // confidence >= min_trusted: `box` is where the image says it went
};

/// One per camera. Frames are pushed in order; follow() moves boxes from the previous frame to
/// the latest one. Allocates nothing of its own once it has seen a frame of the camera's size and
/// as many boxes as it will get (its buffers are kept); OpenCV's filters that build the pyramid
/// allocate small row scratch inside (box_follower.cpp says what).
class BoxFollower {
 public:
  explicit BoxFollower(const BoxFollowerConfig& config = {});

  /// The next frame: an 8-bit gray thumbnail, `scale` thumbnail pixels per frame pixel (the same
  /// for every frame of the camera). Its pyramid is built once, here; the last frame becomes the
  /// previous one.
  void push(const cv::Mat& gray_thumbnail, float scale);
  /// Whether two frames were pushed since the last reset().
  bool ready() const;
  /// Forgets the frames (a gap in the camera's frames: there is nothing to follow across).
  void reset();

  /// Each of `boxes` (frame pixels, where they are in the previous frame) followed into the
  /// latest frame, into `out` (resized to boxes.size()). Before ready(): each box unfollowed.
  void follow(const std::vector<tracker::Box>& boxes, std::vector<FollowedBox>& out);

 private:
  BoxFollowerConfig config_;
  // Implementation's buffers (pyramids of the two frames, points, status, errors), kept across
  // calls: see box_follower.cpp.
  LucasKanadePyramid previous_;
  LucasKanadePyramid latest_;
  std::vector<float> window_scratch_;  // Lucas-Kanade's per-point windows
  std::vector<int> first_point_;       // box i's points: [first_point_[i], first_point_[i + 1])
  std::vector<int> trusted_;           // one box's trusted points, by index
  std::vector<cv::Point2f> from_points_;
  std::vector<cv::Point2f> to_points_;
  std::vector<cv::Point2f> back_points_;
  std::vector<unsigned char> status_;
  std::vector<unsigned char> back_status_;
  std::vector<float> scratch_;
  float scale_{1.F};
  int frames_{0};
};

}  // namespace rtmot::vision
