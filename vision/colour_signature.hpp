#pragma once
// A person's colours in a form the tracker compares (tracker::Appearance): hue-and-saturation
// histograms of the torso and of the legs, from the core of the box only. The core leaves out the
// box's border, where the background shows (a person fills little of the box's sides), the head
// (hair and faces look alike from afar) and the feet (the ground). Hue is kept apart from
// brightness, so that shade and lighting move a person less than a change of clothes does; dark,
// pale and grey pixels, whose hue is noise, are binned by brightness instead.
#include <opencv2/core/mat.hpp>

#include "tracker/box.hpp"

namespace rtmot::vision {

class ColourSignature {
 public:
  /// The signature of `box` (pixels) in the 8-bit BGR `frame`, into `out` (invalid when the box's
  /// core holds too few pixels, or lies outside the frame). Allocates nothing once it has seen a
  /// frame of this size.
  void measure(const cv::Mat& frame, const tracker::Box& box, tracker::Appearance& out);

 private:
  cv::Mat hsv_;  // the frame's size: each part is converted into its own place, no allocation
};

}  // namespace rtmot::vision
