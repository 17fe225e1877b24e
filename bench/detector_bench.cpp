// The SSD detector's own speed on vtest.avi frames: frames are decoded into memory first (through
// rtmot's sources: bench_frames.hpp), so only detect() (resize, normalise, forward pass, decoding,
// NMS) is timed, on OpenCV DNN's CPU path (backend 0) and on XNNPACK (backend 1, where built).
// Needs the model (scripts/fetch_model.sh) and ../shared/data/video/vtest.avi (or
// RTMOT_BENCH_FRAMES=images://DIR). For batches, the CUDA backends and backends called in turn
// (side by side, fairer on a loaded machine): detector_batch_bench.
// Run: build/bench/detector_bench [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include <vector>

#include "bench_frames.hpp"
#include "detector/ssd_detector.hpp"
#include "detector/xnnpack_network.hpp"

namespace {

constexpr int kFrames = 16;       // kept in memory, cycled through
constexpr int kFrameStride = 25;  // spread over the video for varied content

struct Frames {
  std::vector<cv::Mat> images;
  std::string error;
};

const Frames& frames() {
  static const Frames decoded = [] {
    Frames out;
    out.images = rtmot::bench::load_bench_frames(kFrames, kFrameStride, out.error);
    return out;
  }();
  return decoded;
}

void BM_SsdDetect(benchmark::State& state) {
  const auto& images = frames().images;
  if (images.empty()) {
    state.SkipWithError(("no frames: " + frames().error).c_str());
    return;
  }
  // 0 OpenCV's cpu path, 1 XNNPACK fp32, 2 XNNPACK int8 (the committed calibration).
  const auto engine = state.range(0);
  if (engine > 0 && !rtmot::detector::xnnpack_built()) {
    state.SkipWithError("this build has no XNNPACK backend");
    return;
  }
  state.SetLabel(engine == 2 ? "xnnpack-int8" : engine == 1 ? "xnnpack" : "opencv-cpu");
  rtmot::detector::SsdConfig config;
  config.model_path = RTMOT_MODEL_PATH;
  config.int8_ranges = RTMOT_INT8_RANGES_PATH;
  config.backend = engine == 2   ? rtmot::detector::BackendRequest::xnnpack_int8
                   : engine == 1 ? rtmot::detector::BackendRequest::xnnpack
                                 : rtmot::detector::BackendRequest::cpu;
  config.threads = static_cast<int>(state.range(1));
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
    ->ArgNames({"backend", "threads"})
    ->ArgsProduct({{0, 1, 2}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->MinTime(3.0)
    ->UseRealTime();

}  // namespace
