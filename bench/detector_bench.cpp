// The SSD detector's own speed on vtest.avi frames: frames are decoded into memory first, so only
// detect() (resize, normalise, forward pass, decoding, NMS) is timed. Needs the model
// (scripts/fetch_model.sh) and ../shared/data/video/vtest.avi.
// Run: build/bench/detector_bench [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <opencv2/videoio.hpp>
#include <vector>

#include "detector/ssd_detector.hpp"

namespace {

constexpr int kFrames = 16;       // kept in memory, cycled through
constexpr int kFrameStride = 25;  // spread over the video for varied content

std::filesystem::path shared_dir() {
  const char* env = std::getenv("RTMOT_SHARED_DIR");
  return env ? env : RTMOT_SHARED_DIR;
}

const std::vector<cv::Mat>& frames() {
  static const std::vector<cv::Mat> decoded = [] {
    std::vector<cv::Mat> out;
    cv::VideoCapture video((shared_dir() / "data/video/vtest.avi").string(), cv::CAP_FFMPEG);
    cv::Mat image;
    for (int i = 0; static_cast<int>(out.size()) < kFrames && video.read(image); ++i) {
      if (i % kFrameStride == 0) out.push_back(image.clone());
    }
    return out;
  }();
  return decoded;
}

void BM_SsdDetect(benchmark::State& state) {
  const auto& images = frames();
  if (images.empty()) {
    state.SkipWithError("cannot decode vtest.avi: set RTMOT_SHARED_DIR");
    return;
  }
  rtmot::detector::SsdConfig config;
  config.model_path = RTMOT_MODEL_PATH;
  config.backend = rtmot::detector::BackendRequest::cpu;
  config.threads = static_cast<int>(state.range(0));
  config.score_threshold = 0.5F;
  config.classes = {1};
  std::unique_ptr<rtmot::detector::SsdDetector> detector;
  try {
    detector = std::make_unique<rtmot::detector::SsdDetector>(config);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  std::vector<rtmot::tracker::Detection> out;
  std::size_t next = 0;
  std::size_t boxes = 0;
  for (auto _ : state) {
    detector->detect(images[next], static_cast<std::int64_t>(next) + 1, out);
    boxes += out.size();
    next = (next + 1) % images.size();
  }
  state.SetItemsProcessed(state.iterations());  // frames/s
  state.counters["persons_per_frame"] =
      static_cast<double>(boxes) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_SsdDetect)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(3.0)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
