#pragma once
// Pyramidal Lucas-Kanade point tracking (Bouguet's formulation: a 2x2 normal-equation solve per
// point and level, iterated, coarse to fine). Written here rather than taken from OpenCV's
// calcOpticalFlowPyrLK because that lives in OpenCV's video module, which the pinned OpenCV every
// machine builds (scripts/build_opencv.sh: core, imgproc, imgcodecs, dnn; the GPU machine's and
// CI's) does not have; this needs only imgproc's pyrDown and Scharr. Sparse: tens of points per box
// on a thumbnail, so the per-point cost (the previous frame's window sampled once, the next
// frame's re-sampled each iteration at one sub-pixel offset) is what matters.
#include <opencv2/core/mat.hpp>
#include <vector>

namespace rtmot::vision {

struct LucasKanadeConfig {
  int window = 9;           // odd: the window's side at every level, pixels
  int levels = 2;           // pyramid levels above the image itself
  int iterations = 10;      // at most, per level
  float converged = 0.03F;  // stop iterating once a step is this small, pixels
  /// A point whose window's smaller gradient eigenvalue (per pixel, in squared intensity levels
  /// per pixel of slope) is below this has nothing to lock on (a flat wall, the sky): not
  /// followed. 0.1 is OpenCV's default for calcOpticalFlowPyrLK (1e-4 on its scale of Scharr
  /// sums / 2^20), so as permissive: the forward-backward check is what rejects a wrong lock.
  float min_eigenvalue = 0.1F;
};

/// One frame as the tracker needs it: its pyramid (float) and, per level, the gradients that a
/// frame's role as the "from" image needs. Buffers are kept across frames of one size.
class LucasKanadePyramid {
 public:
  void build(const cv::Mat& gray, const LucasKanadeConfig& config);
  int levels() const { return static_cast<int>(image_.size()); }
  const cv::Mat& image(int level) const { return image_[static_cast<std::size_t>(level)]; }
  const cv::Mat& dx(int level) const { return dx_[static_cast<std::size_t>(level)]; }
  const cv::Mat& dy(int level) const { return dy_[static_cast<std::size_t>(level)]; }

 private:
  std::vector<cv::Mat> image_;  // CV_32F, level 0 = the frame
  std::vector<cv::Mat> dx_;
  std::vector<cv::Mat> dy_;
};

/// Where each of `from_points` (pixels of `from`'s level 0) went in `to`; status 1 where it was
/// followed (inside both images, a textured window, a finite solution). `window_scratch` holds
/// one window's samples (kept by the caller: no allocation per call once grown). With `only`
/// (one entry per point), the points whose entry is 0 are not followed (status 0): the round
/// trip back needs only those that went somewhere.
void track_points(const LucasKanadePyramid& from, const LucasKanadePyramid& to,
                  const std::vector<cv::Point2f>& from_points, std::vector<cv::Point2f>& to_points,
                  std::vector<unsigned char>& status, const LucasKanadeConfig& config,
                  std::vector<float>& window_scratch,
                  const std::vector<unsigned char>* only = nullptr);

}  // namespace rtmot::vision
