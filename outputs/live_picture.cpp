#include "outputs/live_picture.hpp"

#include <spdlog/spdlog.h>

#include <opencv2/imgcodecs.hpp>

namespace rtmot::outputs {
namespace {

// A browser shows it well; about 60 kB for a 768x576 frame.
constexpr int kJpegQuality = 80;

}  // namespace

LivePicture::LivePicture(std::uint32_t stream_id, OverlayFlags flags, messages::ClassLabelFn labels)
    : stream_id_(stream_id),
      overlay_(flags, std::move(labels)),
      encoder_([this] { encode_loop(); }) {}

LivePicture::~LivePicture() {
  stop_.store(true, std::memory_order_relaxed);
  frames_.wake_all();
  encoder_.join();
}

void LivePicture::on_frame(const cv::Mat& bgr, const platform::FrameInfo& info) {
  if (!watched()) return;
  SideFrame& slot = frames_.back();
  bgr.copyTo(slot.image);  // same size as last time: no allocation
  slot.info = info;
  frames_.publish(stop_);  // latest mode: never waits
}

void LivePicture::observe(const messages::FrameResult& result) {
  if (!watched() || result.stream_id != stream_id_ || result.source_outage ||
      result.end_of_stream || result.predicted) {
    return;
  }
  messages::FrameResult& slot = results_.back();
  slot.stream_id = result.stream_id;
  slot.frame_number = result.frame_number;
  slot.times = result.times;
  slot.tracks.assign(result.tracks.begin(), result.tracks.end());  // keeps capacity
  results_.publish(stop_);
}

Jpeg LivePicture::next_jpeg(std::uint64_t& sequence, std::chrono::milliseconds wait) {
  std::unique_lock<std::mutex> lock(mutex_);
  if (!fresh_.wait_for(lock, wait, [&] { return sequence_ > sequence && jpeg_; })) return nullptr;
  sequence = sequence_;
  return jpeg_;
}

void LivePicture::encode_loop() {
  std::vector<unsigned char> buffer;
  const std::vector<int> params{cv::IMWRITE_JPEG_QUALITY, kJpegQuality};
  const messages::FrameResult none;
  bool have_tracks = false;
  while (frames_.take(stop_)) {
    if (results_.try_take()) have_tracks = true;
    cv::Mat& image = frames_.front().image;
    if (image.empty()) continue;
    overlay_.draw(image, have_tracks ? results_.front() : none, false, OverlayStats{});
    try {
      cv::imencode(".jpg", image, buffer, params);
    } catch (const cv::Exception& error) {
      spdlog::warn("web: stream {}: cannot encode the picture: {}", stream_id_, error.what());
      continue;
    }
    auto jpeg = std::make_shared<const std::vector<unsigned char>>(buffer);
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      jpeg_ = std::move(jpeg);
      ++sequence_;
    }
    fresh_.notify_all();
    encoded_.fetch_add(1, std::memory_order_relaxed);
  }
}

}  // namespace rtmot::outputs
