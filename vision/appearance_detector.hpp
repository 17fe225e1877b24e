#pragma once
// A Detector around any Detector that gives each detection its appearance from the image it was
// found in (vision/colour_signature.hpp), for the tracker's association (tracker/appearance.hpp).
// The tracker never sees pixels: this is where the image meets the boxes, below the pipeline.
#include <memory>
#include <string>
#include <vector>

#include "detector/detector.hpp"
#include "vision/colour_signature.hpp"

namespace rtmot::vision {

class AppearanceDetector : public detector::Detector {
 public:
  explicit AppearanceDetector(std::unique_ptr<detector::Detector> inner);

  void detect(const cv::Mat& bgr_image, std::int64_t frame_number,
              std::vector<tracker::Detection>& out) override;
  void detect_batch(const cv::Mat* const* images, const std::int64_t* frame_numbers, int count,
                    std::vector<std::vector<tracker::Detection>>& out) override;
  int max_batch() const override { return inner_->max_batch(); }
  std::string describe() const override;

 private:
  void measure(const cv::Mat& image, std::vector<tracker::Detection>& detections);

  std::unique_ptr<detector::Detector> inner_;
  ColourSignature signature_;
};

}  // namespace rtmot::vision
