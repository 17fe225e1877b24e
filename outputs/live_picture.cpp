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
  {
    // Under the mutex: the encoder cannot miss the notification between its check and its wait.
    const std::lock_guard<std::mutex> lock(mutex_);
    stop_.store(true, std::memory_order_relaxed);
  }
  pace_.notify_all();
  frames_.wake_all();
  results_.wake_all();
  encoder_.join();
}

void LivePicture::on_frame(const cv::Mat& bgr, const platform::FrameInfo& info) {
  if (!watched() || !frame_wanted_.load(std::memory_order_relaxed)) return;
  SideFrame& slot = frames_.back();
  bgr.copyTo(slot.image);  // same size as last time: no allocation
  slot.info = info;
  // Cleared before the publish (a release), so the encoder's next request, made after it took
  // this frame, is later in the flag's order than this store.
  frame_wanted_.store(false, std::memory_order_relaxed);
  frames_.publish(stop_);  // latest mode: never waits
}

void LivePicture::observe(const messages::FrameResult& result) {
  // No watched() here: a request made just before the last watcher left is still answered, so
  // the encoder never draws an old frame with tracks found later.
  if (result.frame_number < result_from_.load(std::memory_order_relaxed) ||
      result.stream_id != stream_id_ || result.source_outage || result.end_of_stream ||
      result.predicted) {
    return;
  }
  result_from_.store(kNoRequest, std::memory_order_relaxed);  // before the publish: as on_frame
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
  using Clock = std::chrono::steady_clock;
  constexpr auto kInterval = std::chrono::microseconds(1'000'000 / kMaxPicturesPerSecond);
  std::vector<unsigned char> buffer;
  const std::vector<int> params{cv::IMWRITE_JPEG_QUALITY, kJpegQuality};
  auto next_picture = Clock::now();
  while (!stop_.load(std::memory_order_relaxed)) {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      pace_.wait_until(lock, next_picture, [&] { return stop_.load(std::memory_order_relaxed); });
    }
    frame_wanted_.store(true, std::memory_order_relaxed);
    if (!frames_.take(stop_)) break;  // sleeps while nobody watches: no frame is copied then
    next_picture = Clock::now() + kInterval;
    cv::Mat& image = frames_.front().image;
    if (image.empty()) continue;
    // The tracks of this frame, or of the first frame after it the detector processed.
    result_from_.store(frames_.front().info.frame_number, std::memory_order_relaxed);
    if (!results_.take(stop_)) break;
    overlay_.draw(image, results_.front(), false, OverlayStats{});
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
