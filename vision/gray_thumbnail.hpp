#pragma once
// The small gray copy of a camera frame that image following works on (vision/box_follower.hpp):
// optical flow needs brightness only, and a person's motion between two camera frames is a few
// pixels, which a quarter or half of the frame's side still resolves. Made on the capture thread
// for every frame, so it must be cheap: one area-averaging resize, then a conversion of the small
// picture.
#include <opencv2/core/mat.hpp>

namespace rtmot::vision {

/// Thumbnail pixels per frame pixel for a frame `width` pixels wide: 1/k for the smallest whole k
/// that brings the width to kGrayThumbnailWidth or less (768 -> 1/2, 1920 -> 1/4, 480 -> 1).
float gray_thumbnail_scale(int width);
constexpr int kGrayThumbnailWidth = 480;

class GrayThumbnail {
 public:
  /// `bgr` (8-bit: BGR, BGRA or already gray) at `scale`, into `gray` (8-bit, one channel).
  /// Allocates nothing once `gray` and this object have seen a frame of this size.
  void make(const cv::Mat& bgr, float scale, cv::Mat& gray);

 private:
  cv::Mat small_;  // the resized colour picture, kept
};

}  // namespace rtmot::vision
