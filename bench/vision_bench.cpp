// What the image work of issue 29 costs per frame, on vtest.avi's 768 x 576 frames, one thread:
// - the colour signature (vision/colour_signature.hpp) of 20 person-sized boxes (48 x 120 px, a
//   grid over the frame; the detect stage's thread, after the SSD). docs/appearance.md, "Cost".
// - following 20 such boxes from one frame to the next (vision/box_follower.hpp): the gray
//   half-size thumbnail of a frame (capture's work), the follower's pyramid of it (push), and
//   push + follow of 20 boxes (the track stage's work per camera frame). OpenCV's own thread pool
//   is held to one thread (cv::setNumThreads(1)) so the figures are one core's.
// Reported per frame as wall time and as the process's CPU time (one thread works: a loaded
// machine inflates it less); boxes_per_s for scale.
#include <benchmark/benchmark.h>

#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "bench_frames.hpp"
#include "tracker/appearance.hpp"
#include "vision/box_follower.hpp"
#include "vision/colour_signature.hpp"
#include "vision/gray_thumbnail.hpp"

namespace {

constexpr int kBoxes = 20;

// 20 person-sized boxes in a grid over a 768 x 576 frame.
std::vector<rtmot::tracker::Box> person_boxes() {
  std::vector<rtmot::tracker::Box> boxes;
  const int columns = 5;
  for (int i = 0; i < kBoxes; ++i) {
    const float x = 40.F + static_cast<float>(i % columns) * 140.F;
    const float y = 30.F + static_cast<float>(i / columns) * 130.F;
    boxes.push_back({x, y, 48.F, 120.F});
  }
  return boxes;
}

void BM_ColourSignature(benchmark::State& state) {
  std::string error;
  const std::vector<cv::Mat> frames = rtmot::bench::load_bench_frames(8, 50, error);
  if (frames.empty()) {
    state.SkipWithError(error.c_str());
    return;
  }
  const std::vector<rtmot::tracker::Box> boxes = person_boxes();
  rtmot::vision::ColourSignature signature;
  rtmot::tracker::Appearance out;
  std::size_t frame = 0;
  for (auto _ : state) {
    const cv::Mat& image = frames[frame++ % frames.size()];
    for (const auto& box : boxes) {
      signature.measure(image, box, out);
      benchmark::DoNotOptimize(out);
    }
  }
  state.counters["boxes_per_s"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * kBoxes, benchmark::Counter::kIsRate);
  state.SetLabel(std::to_string(frames.front().cols) + "x" + std::to_string(frames.front().rows) +
                 ", " + std::to_string(kBoxes) + " boxes a frame");
}
BENCHMARK(BM_ColourSignature)
    ->Unit(benchmark::kMicrosecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

// Follower cases: consecutive frames (what the camera gives between detections).
constexpr int kFollowFrames = 8;

// The product's thumbnail (vision/gray_thumbnail.hpp), at the product's scale for the frame.
float thumbnail_scale(const cv::Mat& frame) {
  return rtmot::vision::gray_thumbnail_scale(frame.cols);
}

void BM_GrayThumbnail(benchmark::State& state) {
  cv::setNumThreads(1);
  std::string error;
  const std::vector<cv::Mat> frames = rtmot::bench::load_bench_frames(kFollowFrames, 1, error);
  if (frames.empty()) {
    state.SkipWithError(error.c_str());
    return;
  }
  rtmot::vision::GrayThumbnail maker;
  const float scale = thumbnail_scale(frames.front());
  cv::Mat gray;
  std::size_t frame = 0;
  for (auto _ : state) {
    maker.make(frames[frame++ % frames.size()], scale, gray);
    benchmark::DoNotOptimize(gray.data);
  }
  state.SetLabel(std::to_string(frames.front().cols) + "x" + std::to_string(frames.front().rows) +
                 " -> " + std::to_string(gray.cols) + "x" + std::to_string(gray.rows) + " gray");
}
BENCHMARK(BM_GrayThumbnail)->Unit(benchmark::kMicrosecond)->MeasureProcessCPUTime()->UseRealTime();

struct Thumbnails {
  std::vector<cv::Mat> gray;
  float scale{1.F};
};

// vtest.avi's first frames as the pipeline's thumbnails; none (and the benchmark skipped) when
// the video cannot be read.
Thumbnails thumbnails_or_skip(benchmark::State& state) {
  cv::setNumThreads(1);
  std::string error;
  const std::vector<cv::Mat> frames = rtmot::bench::load_bench_frames(kFollowFrames, 1, error);
  Thumbnails thumbnails;
  if (frames.empty()) {
    state.SkipWithError(error.c_str());
    return thumbnails;
  }
  rtmot::vision::GrayThumbnail maker;
  thumbnails.scale = thumbnail_scale(frames.front());
  for (const auto& frame : frames) {
    cv::Mat gray;
    maker.make(frame, thumbnails.scale, gray);
    thumbnails.gray.push_back(gray);
  }
  return thumbnails;
}

// push() alone: the pyramid with its derivatives, once per camera frame.
void BM_BoxFollowerPush(benchmark::State& state) {
  const Thumbnails thumbnails = thumbnails_or_skip(state);
  if (thumbnails.gray.empty()) return;
  rtmot::vision::BoxFollower follower;
  std::size_t frame = 0;
  for (auto _ : state)
    follower.push(thumbnails.gray[frame++ % thumbnails.gray.size()], thumbnails.scale);
}
BENCHMARK(BM_BoxFollowerPush)
    ->Unit(benchmark::kMicrosecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

// A camera frame's whole follower work: push() and follow() of 20 boxes (4 of them, on this grid,
// partly outside the frame, as at a frame's edges).
void BM_BoxFollowerFollow(benchmark::State& state) {
  const Thumbnails thumbnails = thumbnails_or_skip(state);
  if (thumbnails.gray.empty()) return;
  const std::vector<rtmot::tracker::Box> boxes = person_boxes();
  rtmot::vision::BoxFollower follower;
  follower.push(thumbnails.gray.back(), thumbnails.scale);
  std::vector<rtmot::vision::FollowedBox> out;
  std::size_t frame = 0;
  int followed = 0;
  for (auto _ : state) {
    follower.push(thumbnails.gray[frame++ % thumbnails.gray.size()], thumbnails.scale);
    follower.follow(boxes, out);
    for (const auto& box : out) followed += box.followed ? 1 : 0;
  }
  state.counters["boxes_per_s"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * kBoxes, benchmark::Counter::kIsRate);
  state.counters["followed_share"] =
      static_cast<double>(followed) / (static_cast<double>(state.iterations()) * kBoxes);
  state.SetLabel(std::to_string(thumbnails.gray.front().cols) + "x" +
                 std::to_string(thumbnails.gray.front().rows) + " gray, " + std::to_string(kBoxes) +
                 " boxes a frame");
}
BENCHMARK(BM_BoxFollowerFollow)
    ->Unit(benchmark::kMicrosecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

}  // namespace
