#pragma once
// vtest.avi frames for the detector benchmarks, read through the product's own sources, never
// OpenCV's videoio: RTMOT_BENCH_FRAMES=URI (any source URI, e.g. images://DIR for a folder of
// extracted frames on a machine without GStreamer codecs), else file://../shared/.../vtest.avi
// through GStreamer.
#include <cstdlib>
#include <filesystem>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "platform/video_source.hpp"

namespace rtmot::bench {

inline std::string bench_frames_uri() {
  if (const char* uri = std::getenv("RTMOT_BENCH_FRAMES")) return uri;
  const char* env = std::getenv("RTMOT_SHARED_DIR");
  const std::filesystem::path shared = env ? env : RTMOT_SHARED_DIR;
  return "file://" + (shared / "data/video/vtest.avi").string();
}

/// `count` frames, every `stride`-th of vtest.avi (every one of RTMOT_BENCH_FRAMES's, which holds
/// frames chosen already), decoded into memory (empty on failure, with the reason in `error`).
inline std::vector<cv::Mat> load_bench_frames(int count, int stride, std::string& error) {
  if (std::getenv("RTMOT_BENCH_FRAMES") != nullptr) stride = 1;
  std::vector<cv::Mat> frames;
  try {
    const auto source = platform::open_video_source(bench_frames_uri());
    cv::Mat image;
    platform::FrameInfo info;
    for (int i = 0; static_cast<int>(frames.size()) < count; ++i) {
      if (source->read(image, info) != platform::ReadStatus::frame) break;
      if (i % stride == 0) frames.push_back(image.clone());
    }
  } catch (const std::exception& e) {
    error = e.what();
  }
  if (frames.empty() && error.empty()) error = "no frames from " + bench_frames_uri();
  return frames;
}

}  // namespace rtmot::bench
