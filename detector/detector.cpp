#include "detector/detector.hpp"

#include <cstddef>
#include <stdexcept>

namespace rtmot::detector {

void Detector::detect_batch(const cv::Mat* const* images, const std::int64_t* frame_numbers,
                            int count, std::vector<std::vector<tracker::Detection>>& out) {
  if (count < 1) throw std::invalid_argument("Detector::detect_batch: count must be >= 1");
  if (out.size() < static_cast<std::size_t>(count)) out.resize(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    detect(*images[i], frame_numbers[i], out[static_cast<std::size_t>(i)]);
  }
}

}  // namespace rtmot::detector
