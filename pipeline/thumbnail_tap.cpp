#include "pipeline/thumbnail_tap.hpp"

namespace rtmot::pipeline {

ThumbnailTap::ThumbnailTap(std::size_t capacity)
    : queue_(capacity, [](Thumbnail&) {}) {}  // each slot's buffer is made by its first frame

void ThumbnailTap::on_frame(const cv::Mat& bgr, const platform::FrameInfo& info) {
  if (bgr.empty()) return;
  Thumbnail* slot = queue_.try_claim();
  if (slot == nullptr) {
    dropped_.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  slot->scale = vision::gray_thumbnail_scale(bgr.cols);
  maker_.make(bgr, slot->scale, slot->gray);
  slot->info = info;
  queue_.publish();
}

}  // namespace rtmot::pipeline
