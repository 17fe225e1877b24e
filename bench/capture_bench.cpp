// Capture cost per frame: GStreamer decode/convert plus the copy into the reused cv::Mat that
// VideoSource::read() does. Run: build/bench/capture_bench (RTMOT_SHARED_DIR overrides ../shared).
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <memory>
#include <opencv2/core.hpp>
#include <string>

#include "common/input_error.hpp"
#include "platform/video_source.hpp"

namespace {

std::string vtest_uri() {
  const char* env = std::getenv("RTMOT_SHARED_DIR");
  const std::filesystem::path shared = env != nullptr ? env : RTMOT_SHARED_DIR;
  return (shared / "data/video/vtest.avi").string();
}

// Reads frames from `uri` one per iteration, reopening (untimed) when the stream ends.
void read_frames(benchmark::State& state, const std::string& uri) {
  std::unique_ptr<rtmot::platform::VideoSource> source;
  try {
    source = rtmot::platform::open_video_source(uri);
  } catch (const rtmot::InputError& error) {
    state.SkipWithError(error.what());
    return;
  }
  cv::Mat frame;
  rtmot::platform::FrameInfo info;
  for (auto _ : state) {
    auto status = source->read(frame, info);
    if (status == rtmot::platform::ReadStatus::end_of_stream) {
      state.PauseTiming();
      source = rtmot::platform::open_video_source(uri);
      state.ResumeTiming();
      status = source->read(frame, info);
    }
    if (status != rtmot::platform::ReadStatus::frame) {
      state.SkipWithError(source->last_error().c_str());
      return;
    }
    benchmark::DoNotOptimize(frame.data);
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["width"] = frame.cols;
  state.counters["height"] = frame.rows;
}

// vtest.avi: MS-MPEG4v3 decode (avdec_msmpeg4) + I420->BGR + copy, 768x576.
void BM_ReadVtestFile(benchmark::State& state) {
  read_frames(state, vtest_uri());
}
BENCHMARK(BM_ReadVtestFile)->Unit(benchmark::kMillisecond)->UseRealTime();

// videotestsrc (no decode): the conversion and copy alone, at common camera sizes.
void BM_ReadTestPattern(benchmark::State& state) {
  read_frames(state, "test://smpte?width=" + std::to_string(state.range(0)) +
                         "&height=" + std::to_string(state.range(1)));
}
BENCHMARK(BM_ReadTestPattern)
    ->Args({640, 480})
    ->Args({1280, 720})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
