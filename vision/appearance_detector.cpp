#include "vision/appearance_detector.hpp"

#include <utility>

namespace rtmot::vision {

AppearanceDetector::AppearanceDetector(std::unique_ptr<detector::Detector> inner)
    : inner_(std::move(inner)) {}

void AppearanceDetector::detect(const cv::Mat& bgr_image, std::int64_t frame_number,
                                std::vector<tracker::Detection>& out) {
  inner_->detect(bgr_image, frame_number, out);
  measure(bgr_image, out);
}

void AppearanceDetector::detect_batch(const cv::Mat* const* images,
                                      const std::int64_t* frame_numbers, int count,
                                      std::vector<std::vector<tracker::Detection>>& out) {
  inner_->detect_batch(images, frame_numbers, count, out);
  for (int i = 0; i < count; ++i) measure(*images[i], out[static_cast<std::size_t>(i)]);
}

std::string AppearanceDetector::describe() const {
  return inner_->describe() + ", a colour signature per detection (detector.appearance)";
}

void AppearanceDetector::measure(const cv::Mat& image,
                                 std::vector<tracker::Detection>& detections) {
  for (tracker::Detection& detection : detections)
    signature_.measure(image, detection.box, detection.appearance);
}

}  // namespace rtmot::vision
