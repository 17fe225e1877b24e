// What the image work of issue 29 costs per frame: the colour signature
// (vision/colour_signature.hpp) of 20 person-sized boxes (48 x 120 px, a grid over the frame) on
// vtest.avi's 768 x 576 frames, one thread (the detect stage's, after the SSD). Reported per frame
// as wall time and as the process's CPU time (one thread works: a loaded machine inflates it less);
// boxes_per_s for scale. docs/appearance.md, "Cost".
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "bench_frames.hpp"
#include "tracker/appearance.hpp"
#include "vision/colour_signature.hpp"

namespace {

constexpr int kBoxes = 20;

void BM_ColourSignature(benchmark::State& state) {
  std::string error;
  const std::vector<cv::Mat> frames = rtmot::bench::load_bench_frames(8, 50, error);
  if (frames.empty()) {
    state.SkipWithError(error.c_str());
    return;
  }
  std::vector<rtmot::tracker::Box> boxes;
  const int columns = 5;
  for (int i = 0; i < kBoxes; ++i) {
    const float x = 40.F + static_cast<float>(i % columns) * 140.F;
    const float y = 30.F + static_cast<float>(i / columns) * 130.F;
    boxes.push_back({x, y, 48.F, 120.F});
  }
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

}  // namespace
