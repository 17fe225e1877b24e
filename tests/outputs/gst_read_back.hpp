#pragma once
// Reads a video back with a GStreamer pipeline started by the test: counts the decoded frames and
// keeps one of them (BGR) for checks and PNGs.
#include <chrono>
#include <functional>
#include <opencv2/core/mat.hpp>
#include <string>

namespace rtmot::test {

struct ReadBack {
  int frames{0};
  cv::Mat saved;  // the frame asked for, BGR
};

/// Runs `description` (ending in `appsink name=out`) until EOS, an error, `stop_after` frames or
/// `limit`; keeps frame `save_index` (0-based). `once_playing` runs right after it starts.
ReadBack read_back(
    const std::string& description, int save_index, int stop_after, std::chrono::milliseconds limit,
    const std::function<void()>& once_playing = [] {});

/// Appended to a decoder: converts to BGR into `appsink name=out`.
extern const std::string to_bgr_sink;

}  // namespace rtmot::test
