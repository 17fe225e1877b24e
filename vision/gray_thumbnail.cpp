#include "vision/gray_thumbnail.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace rtmot::vision {

float gray_thumbnail_scale(int width) {
  if (width <= kGrayThumbnailWidth) return 1.F;
  const int divisor = (width + kGrayThumbnailWidth - 1) / kGrayThumbnailWidth;
  return 1.F / static_cast<float>(divisor);
}

void GrayThumbnail::make(const cv::Mat& bgr, float scale, cv::Mat& gray) {
  const cv::Size size(std::max(1, static_cast<int>(std::lround(bgr.cols * scale))),
                      std::max(1, static_cast<int>(std::lround(bgr.rows * scale))));
  cv::resize(bgr, small_, size, 0.0, 0.0, cv::INTER_AREA);
  if (small_.channels() == 3) {
    cv::cvtColor(small_, gray, cv::COLOR_BGR2GRAY);
  } else if (small_.channels() == 4) {
    cv::cvtColor(small_, gray, cv::COLOR_BGRA2GRAY);
  } else {
    small_.copyTo(gray);
  }
}

}  // namespace rtmot::vision
