#include "platform/oriented_source.hpp"

#include <opencv2/core.hpp>
#include <utility>

namespace rtmot::platform {

bool swaps_sides(Orientation orientation) {
  switch (orientation) {
    case Orientation::clockwise:
    case Orientation::counterclockwise:
    case Orientation::upper_left_diagonal:
    case Orientation::upper_right_diagonal:
      return true;
    default:
      return false;
  }
}

void orient(const cv::Mat& in, cv::Mat& out, Orientation orientation, cv::Mat& scratch) {
  switch (orientation) {
    case Orientation::none:
      in.copyTo(out);
      return;
    case Orientation::clockwise:
      cv::rotate(in, out, cv::ROTATE_90_CLOCKWISE);
      return;
    case Orientation::rotate_180:
      cv::rotate(in, out, cv::ROTATE_180);
      return;
    case Orientation::counterclockwise:
      cv::rotate(in, out, cv::ROTATE_90_COUNTERCLOCKWISE);
      return;
    case Orientation::horizontal:
      cv::flip(in, out, 1);
      return;
    case Orientation::vertical:
      cv::flip(in, out, 0);
      return;
    case Orientation::upper_left_diagonal:
      cv::transpose(in, out);
      return;
    case Orientation::upper_right_diagonal:
      // The anti-diagonal mirror: transposed, then turned half round.
      cv::transpose(in, scratch);
      cv::rotate(scratch, out, cv::ROTATE_180);
      return;
  }
}

OrientedSource::OrientedSource(std::unique_ptr<VideoSource> inner, Orientation orientation)
    : inner_(std::move(inner)), orientation_(orientation), info_(inner_->info()) {
  if (swaps_sides(orientation_)) std::swap(info_.width, info_.height);
}

ReadStatus OrientedSource::read(cv::Mat& bgr, FrameInfo& info) {
  const ReadStatus status = inner_->read(decoded_, info);
  if (status != ReadStatus::frame) return status;
  orient(decoded_, bgr, orientation_, scratch_);
  // A camera that opened late (cold start) or came back at another size: its size as delivered.
  info_.width = bgr.cols;
  info_.height = bgr.rows;
  return status;
}

}  // namespace rtmot::platform
