#pragma once
// Parts shared by the pipeline tests: real and synthetic sources, detectors with known output, a
// sink that keeps every message.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "detector/detector.hpp"
#include "messages/frame_result.hpp"
#include "pipeline/pipeline.hpp"
#include "platform/clock.hpp"
#include "platform/video_source.hpp"
#include "shared_data.hpp"
#include "tracker/tracker_config.hpp"

namespace rtmot::pipeline::test_parts {

using platform::FrameInfo;
using platform::ReadStatus;

// A recording decoded by the product's own GStreamer source (the product has no OpenCV videoio),
// pts from the frame index (vtest.avi is constant-rate), so every test sees the same timing.
class FileSource : public platform::VideoSource {
 public:
  explicit FileSource(const std::string& path) : source_(platform::open_video_source(path)) {
    info_ = source_->info();
    info_.uri = path;
  }
  ReadStatus read(cv::Mat& bgr, FrameInfo& info) override {
    if (source_->read(bgr, info) != ReadStatus::frame) return ReadStatus::end_of_stream;
    ++frames_;
    info.frame_number = frames_;
    info.pts_ns = std::llround(static_cast<double>(frames_ - 1) * 1e9 / info_.fps);
    info.capture_ns = platform::steady_now_ns();
    return ReadStatus::frame;
  }
  const platform::SourceInfo& info() const override { return info_; }
  std::string last_error() const override { return source_->last_error(); }

 private:
  std::unique_ptr<platform::VideoSource> source_;
  platform::SourceInfo info_;
  std::int64_t frames_{0};
};

// Two people walking in opposite directions, whatever the image.
class FixedBoxDetector : public detector::Detector {
 public:
  void detect(const cv::Mat& image, std::int64_t frame_number,
              std::vector<tracker::Detection>& out) override {
    EXPECT_FALSE(image.empty());
    out.clear();
    const auto f = static_cast<float>(frame_number);
    out.push_back({{100.F + 2.F * f, 200.F, 50.F, 120.F}, 0.9F, 1});
    out.push_back({{600.F - 1.5F * f, 220.F, 55.F, 125.F}, 0.8F, 1});
  }
  std::string describe() const override { return "fixed boxes"; }
};

struct Collected {
  std::vector<messages::FrameResult> results;
  int flushes{0};
};

class CollectingSink : public messages::TrackSink {
 public:
  explicit CollectingSink(Collected& into) : into_(into) {}
  void write(const messages::FrameResult& result) override { into_.results.push_back(result); }
  void flush() override { ++into_.flushes; }

 private:
  Collected& into_;
};

inline std::vector<std::unique_ptr<messages::TrackSink>> sinks_into(Collected& collected) {
  std::vector<std::unique_ptr<messages::TrackSink>> sinks;
  sinks.push_back(std::make_unique<CollectingSink>(collected));
  return sinks;
}

inline tracker::TrackerConfig sort_for(double fps) {
  auto config = tracker::TrackerConfig::sort_preset();
  config.frame_rate = fps;
  config.image_width = 768.F;
  config.image_height = 576.F;
  return config;
}

inline PipelineOptions quiet(PlaybackMode mode) {
  PipelineOptions options;
  options.playback = mode;
  options.stats_interval_s = 0.0;
  return options;
}

inline std::string vtest_path() {
  return test::shared_path("data/video/vtest.avi").string();
}

// A fast live camera: numbered frames carrying a pattern derived from their number.
class PatternSource : public platform::VideoSource {
 public:
  explicit PatternSource(std::int64_t frames) : frames_(frames) {
    info_.uri = "pattern://";
    info_.live = true;
    info_.fps = 1000.0;
  }
  ReadStatus read(cv::Mat& bgr, FrameInfo& info) override {
    if (next_ > frames_) return ReadStatus::end_of_stream;
    bgr.create(24, 32, CV_8UC3);
    bgr.setTo(cv::Scalar::all(static_cast<double>(next_ % 251)));
    info.frame_number = next_;
    info.pts_ns = next_ * 1'000'000;
    info.capture_ns = platform::steady_now_ns();
    ++next_;
    if (next_ % 7 == 0) std::this_thread::sleep_for(std::chrono::microseconds(300));
    return ReadStatus::frame;
  }
  const platform::SourceInfo& info() const override { return info_; }
  std::string last_error() const override { return {}; }

 private:
  std::int64_t frames_;
  std::int64_t next_{1};
  platform::SourceInfo info_;
};

}  // namespace rtmot::pipeline::test_parts
