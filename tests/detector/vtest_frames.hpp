#pragma once
// Frames of ../shared/data/video/vtest.avi for the detector tests, read through the product's own
// sources (the product does not use OpenCV's videoio): GStreamer (file://) by default, or, where
// GStreamer cannot decode it (the GPU test machine carries no codec plugins), an image folder of
// frames extracted beforehand named by frame number (RTMOT_VTEST_FRAMES=DIR holding 1.png, 51.png,
// ...: see docs/gpu.md for the command).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <opencv2/core/mat.hpp>
#include <opencv2/imgcodecs.hpp>
#include <set>
#include <string>

#include "platform/video_source.hpp"
#include "shared_data.hpp"

namespace rtmot::test {

/// True when the frames come from RTMOT_VTEST_FRAMES, i.e. decoded as the reference detections'
/// frames were (FFmpeg's swscale); GStreamer's videoconvert gives slightly other pixels.
inline bool vtest_frames_decoded_as_reference() {
  return std::getenv("RTMOT_VTEST_FRAMES") != nullptr;
}

/// True where the tests run under an emulator: scripts/cross_build.sh sets
/// RTMOT_TEST_UNDER_EMULATION=1 for its qemu run, where one SSD forward takes about 15 s.
inline bool under_emulation() {
  const char* value = std::getenv("RTMOT_TEST_UNDER_EMULATION");
  return value != nullptr && std::string(value) == "1";
}

/// The frames the SSD is checked on against references: 1, 51, ..., 751 (16, the reference's).
/// Under emulation the first four (1, 51, 101, 151): there the question is whether aarch64's
/// kernels compute the same numbers, which four frames and about 70 detections answer, and the 16
/// took 25 of the aarch64 stage's 40 minutes of tests (CI's whole run has 90).
inline std::set<int> reference_frame_numbers() {
  constexpr int first = 1;
  constexpr int step = 50;
  const int last = under_emulation() ? 151 : 751;
  std::set<int> numbers;
  for (int frame = first; frame <= last; frame += step) numbers.insert(frame);
  return numbers;
}

/// The frames `wanted` (1-based numbers) of vtest.avi, by number. Fails the test naming what is
/// missing when a frame cannot be had.
inline std::map<int, cv::Mat> vtest_frames(const std::set<int>& wanted) {
  std::map<int, cv::Mat> frames;
  if (const char* dir = std::getenv("RTMOT_VTEST_FRAMES")) {
    for (const int number : wanted) {
      const auto path = std::filesystem::path(dir) / (std::to_string(number) + ".png");
      cv::Mat image = cv::imread(path.string(), cv::IMREAD_COLOR);
      if (image.empty()) ADD_FAILURE() << "RTMOT_VTEST_FRAMES: cannot read " << path;
      frames[number] = image;
    }
    return frames;
  }
  const auto video_path = shared_path("data/video/vtest.avi");
  if (!std::filesystem::exists(video_path)) {
    ADD_FAILURE() << "missing test data file: " << video_path;
    return frames;
  }
  const auto source = platform::open_video_source("file://" + video_path.string());
  cv::Mat image;
  platform::FrameInfo info;
  const int last = wanted.empty() ? 0 : *wanted.rbegin();
  for (int number = 1; number <= last; ++number) {
    if (source->read(image, info) != platform::ReadStatus::frame) {
      ADD_FAILURE() << video_path << " ended (or failed: " << source->last_error()
                    << ") before frame " << number;
      break;
    }
    if (wanted.count(number) != 0) frames[number] = image.clone();
  }
  return frames;
}

}  // namespace rtmot::test
