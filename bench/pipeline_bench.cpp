// End-to-end throughput of the pipeline against its detector's own throughput, in every-frame mode
// on vtest.avi with the SSD on the CPU: the pipeline overlaps decoding, tracking and sending with
// detection, so its FPS should stay within a few percent of the detector's (goal: >= 0.97x).
// Both FPS come from the same run: detector FPS = processed frames / time spent inside detect().
// Needs the model (scripts/fetch_model.sh) and ../shared/data/video/vtest.avi.
// Run: build/bench/pipeline_bench
#include <benchmark/benchmark.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <memory>

#include "detector/ssd_detector.hpp"
#include "pipeline/pipeline.hpp"
#include "runner/source_factory.hpp"
#include "tracker/tracker_config.hpp"

namespace {

constexpr std::int64_t kFrames = 150;

std::filesystem::path shared_dir() {
  const char* env = std::getenv("RTMOT_SHARED_DIR");
  return env ? env : RTMOT_SHARED_DIR;
}

// A sink that keeps nothing: the benchmark measures the pipeline, not an output.
class NullSink : public rtmot::messages::TrackSink {
 public:
  void write(const rtmot::messages::FrameResult&) override {}
  void flush() override {}
};

void BM_PipelineEveryFrameVsDetector(benchmark::State& state) {
  using namespace rtmot;
  for (auto _ : state) {
    std::unique_ptr<pipeline::Pipeline> run;
    try {
      detector::SsdConfig ssd;
      ssd.model_path = RTMOT_MODEL_PATH;
      ssd.backend = detector::BackendRequest::cpu;
      ssd.threads = static_cast<int>(state.range(0));
      auto source = runner::open_source((shared_dir() / "data/video/vtest.avi").string(), {});
      auto tracker_config = tracker::TrackerConfig::sort_preset();
      tracker_config.frame_rate = source->info().fps;
      std::vector<std::unique_ptr<messages::TrackSink>> sinks;
      sinks.push_back(std::make_unique<NullSink>());
      pipeline::PipelineOptions options;
      options.playback = pipeline::PlaybackMode::every_frame;
      options.max_frames = kFrames;
      options.stats_interval_s = 0.0;
      run = std::make_unique<pipeline::Pipeline>(std::move(source),
                                                 std::make_unique<detector::SsdDetector>(ssd),
                                                 tracker_config, std::move(sinks), options);
    } catch (const std::exception& error) {
      state.SkipWithError(error.what());
      return;
    }
    const std::atomic<bool> stop{false};
    const pipeline::PipelineReport report = run->run(stop);
    state.counters["pipeline_fps"] = report.fps;
    state.counters["detector_fps"] = report.detector_fps;
    state.counters["ratio"] = report.detector_fps > 0.0 ? report.fps / report.detector_fps : 0.0;
    state.counters["e2e_p50_ms"] =
        static_cast<double>(report.latency.end_to_end.quantile_ns(0.5)) / 1e6;
    state.counters["e2e_p99_ms"] =
        static_cast<double>(report.latency.end_to_end.quantile_ns(0.99)) / 1e6;
  }
}
BENCHMARK(BM_PipelineEveryFrameVsDetector)
    ->Arg(1)
    ->Arg(2)
    ->Iterations(1)
    ->Unit(benchmark::kSecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
