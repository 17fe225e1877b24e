// The pipeline against its detector, on vtest.avi with the SSD on the CPU (docs/architecture.md,
// "Measured"). Run it right after bench/detector_bench on the same machine:
//   build/bench/detector_bench && build/bench/pipeline_bench
// - BM_PipelineEveryFrameVsDetector: every-frame mode; the pipeline overlaps decoding, tracking and
//   sending with detection, so its FPS should stay within a few percent of the detector's (goal:
//   >= 0.97x detector_bench at the same thread count). detector_fps is the same run's processed
//   frames / time inside detect().
// - BM_PipelineRealtimeWaitCost: realtime mode (10 fps, the detector is idle most of the time):
//   the CPU burnt by the threads that only hand frames over (rtmot-capture, -track, -sink; goal:
//   < 3% of one core together) and the frame age at message out (capture -> sent p99; goal: <=
//   the detector's p99 + 5 ms).
// - BM_PipelineVsDetectorPaired: on a shared machine the detector's speed drifts by 2x within
//   minutes, so a pipeline run and a detector_bench run minutes apart do not compare. This one
//   alternates, five times, 40 frames of the detector alone (detect() on frames decoded into
//   memory, as detector_bench) with 40 frames of the every-frame pipeline, and reports the median
//   of the five ratios pipeline FPS / detector-alone FPS (goal >= 0.97).
// - BM_MultiSourceEveryFrame: N copies of vtest.avi through one batched detector, every frame:
//   aggregate FPS (all sources) against one source, mean batch size, detector time per image.
// threads:0 is OpenCV's default thread setting (the SSD does not call cv::setNumThreads); that is
// only what it says in a process where no earlier benchmark set a count (the setting is global):
// run those rows alone, e.g. --benchmark_filter='threads:0'. opencv_threads shows what was in
// force. Needs the model (scripts/fetch_model.sh) and ../shared/data/video/vtest.avi.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <opencv2/core/utility.hpp>

#include "bench/thread_cpu.hpp"
#include "detector/ssd_detector.hpp"
#include "pipeline/pipeline.hpp"
#include "runner/source_factory.hpp"
#include "tracker/tracker_config.hpp"

namespace {

using namespace rtmot;

std::filesystem::path shared_dir() {
  const char* env = std::getenv("RTMOT_SHARED_DIR");
  return env ? env : RTMOT_SHARED_DIR;
}

// A sink that keeps nothing: the benchmark measures the pipeline, not an output.
class NullSink : public messages::TrackSink {
 public:
  void write(const messages::FrameResult&) override {}
  void flush() override {}
};

// `sources` copies of vtest.avi, each its own stream, through one SSD on the CPU.
std::unique_ptr<pipeline::Pipeline> vtest_pipeline(pipeline::PlaybackMode playback, int threads,
                                                   std::int64_t frames, int sources = 1) {
  detector::SsdConfig ssd;
  ssd.model_path = RTMOT_MODEL_PATH;
  ssd.backend = detector::BackendRequest::cpu;
  ssd.threads = threads;
  ssd.max_batch = sources;  // one forward pass per batch (needs the dynamic-batch model, format 2)
  std::vector<pipeline::PipelineInput> inputs(static_cast<std::size_t>(sources));
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    inputs[i].source = runner::open_source((shared_dir() / "data/video/vtest.avi").string(), {});
    inputs[i].tracker = tracker::TrackerConfig::sort_preset();
    inputs[i].tracker.frame_rate = inputs[i].source->info().fps;
    inputs[i].stream_id = static_cast<std::uint32_t>(i);
  }
  std::vector<std::unique_ptr<pipeline::FrameConsumer>> consumers;
  consumers.push_back(std::make_unique<pipeline::TrackSinkConsumer>(std::make_unique<NullSink>()));
  pipeline::PipelineOptions options;
  options.playback = playback;
  options.max_frames = frames;
  options.stats_interval_s = 0.0;
  return std::make_unique<pipeline::Pipeline>(std::move(inputs),
                                              std::make_unique<detector::SsdDetector>(ssd),
                                              std::move(consumers), options);
}

double ms(std::int64_t ns) {
  return static_cast<double>(ns) / 1e6;
}

void BM_PipelineEveryFrameVsDetector(benchmark::State& state) {
  for (auto _ : state) {
    std::unique_ptr<pipeline::Pipeline> run;
    try {
      run = vtest_pipeline(pipeline::PlaybackMode::every_frame, static_cast<int>(state.range(0)),
                           150);
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
        ms(report.latency.of(pipeline::Stage::end_to_end).quantile_ns(0.5));
    state.counters["e2e_p99_ms"] =
        ms(report.latency.of(pipeline::Stage::end_to_end).quantile_ns(0.99));
    state.counters["opencv_threads"] = cv::getNumThreads();
  }
}
BENCHMARK(BM_PipelineEveryFrameVsDetector)
    ->ArgName("threads")
    ->Arg(0)
    ->Arg(1)
    ->Arg(2)
    ->Iterations(1)
    ->Unit(benchmark::kSecond)
    ->UseRealTime();

void BM_PipelineRealtimeWaitCost(benchmark::State& state) {
  for (auto _ : state) {
    std::unique_ptr<pipeline::Pipeline> run;
    try {
      run = vtest_pipeline(pipeline::PlaybackMode::realtime, static_cast<int>(state.range(0)), 150);
    } catch (const std::exception& error) {
      state.SkipWithError(error.what());
      return;
    }
    const std::atomic<bool> stop{false};
    bench::ThreadCpuSampler cpu;
    const auto start = std::chrono::steady_clock::now();
    const pipeline::PipelineReport report = run->run(stop);
    const std::chrono::duration<double> wall = std::chrono::steady_clock::now() - start;
    cpu.stop();
    const auto percent = [&](const char* name) {
      return 100.0 * cpu.cpu_seconds(name) / wall.count();
    };
    state.counters["capture_cpu_pct"] = percent("rtmot-capture");
    state.counters["track_cpu_pct"] = percent("rtmot-track");
    state.counters["sink_cpu_pct"] = percent("rtmot-sink");
    state.counters["handoff_cpu_pct"] =
        percent("rtmot-capture") + percent("rtmot-track") + percent("rtmot-sink");
    state.counters["detect_cpu_pct"] = percent("rtmot-detect");
    state.counters["processed"] = static_cast<double>(report.frames_processed);
    state.counters["detect_p50_ms"] =
        ms(report.latency.of(pipeline::Stage::detect).quantile_ns(0.5));
    state.counters["detect_p99_ms"] =
        ms(report.latency.of(pipeline::Stage::detect).quantile_ns(0.99));
    state.counters["age_p50_ms"] =
        ms(report.latency.of(pipeline::Stage::end_to_end).quantile_ns(0.5));
    state.counters["age_p99_ms"] =
        ms(report.latency.of(pipeline::Stage::end_to_end).quantile_ns(0.99));
    state.counters["age_p99_minus_detect_p99_ms"] =
        ms(report.latency.of(pipeline::Stage::end_to_end).quantile_ns(0.99) -
           report.latency.of(pipeline::Stage::detect).quantile_ns(0.99));
    // What the age adds to the detector, stage by stage: waiting for the detector (queued: the
    // detector was busy with the previous frame, or slow to wake), tracking, handing to the sinks.
    state.counters["queued_p99_ms"] =
        ms(report.latency.of(pipeline::Stage::queue).quantile_ns(0.99));
    state.counters["track_p99_ms"] =
        ms(report.latency.of(pipeline::Stage::track).quantile_ns(0.99));
    state.counters["send_p99_ms"] = ms(report.latency.of(pipeline::Stage::sink).quantile_ns(0.99));
  }
}
BENCHMARK(BM_PipelineRealtimeWaitCost)
    ->ArgName("threads")
    ->Arg(2)
    ->Iterations(1)
    ->Unit(benchmark::kSecond)
    ->UseRealTime();

// Frames of vtest.avi decoded into memory through rtmot's own source (no videoio), as
// detector_bench does: every 25th of the first 400.
std::vector<cv::Mat> decoded_frames() {
  std::vector<cv::Mat> frames;
  auto source = runner::open_source((shared_dir() / "data/video/vtest.avi").string(), {});
  cv::Mat image;
  platform::FrameInfo info;
  for (int i = 0; frames.size() < 16 && source->read(image, info) == platform::ReadStatus::frame;
       ++i) {
    if (i % 25 == 0) frames.push_back(image.clone());
  }
  return frames;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values.empty() ? 0.0 : values[values.size() / 2];
}

void BM_PipelineVsDetectorPaired(benchmark::State& state) {
  constexpr int kRounds = 5;
  constexpr int kFrames = 40;
  const int threads = static_cast<int>(state.range(0));
  for (auto _ : state) {
    std::vector<double> alone_fps;
    std::vector<double> pipeline_fps;
    std::vector<double> ratios;
    try {
      const std::vector<cv::Mat> frames = decoded_frames();
      if (frames.empty()) throw std::runtime_error("cannot decode vtest.avi");
      detector::SsdConfig ssd;
      ssd.model_path = RTMOT_MODEL_PATH;
      ssd.backend = detector::BackendRequest::cpu;
      ssd.threads = threads;
      detector::SsdDetector alone(ssd);
      std::vector<tracker::Detection> boxes;
      alone.detect(frames[0], 1, boxes);  // warm-up, as the pipeline's detector had at start-up
      for (int round = 0; round < kRounds; ++round) {
        const auto start = std::chrono::steady_clock::now();
        for (int i = 0; i < kFrames; ++i) {
          alone.detect(frames[static_cast<std::size_t>(i) % frames.size()], i + 1, boxes);
        }
        const std::chrono::duration<double> took = std::chrono::steady_clock::now() - start;
        alone_fps.push_back(kFrames / took.count());
        const std::atomic<bool> stop{false};
        const auto report =
            vtest_pipeline(pipeline::PlaybackMode::every_frame, threads, kFrames)->run(stop);
        pipeline_fps.push_back(report.fps);
        ratios.push_back(report.fps / alone_fps.back());
      }
    } catch (const std::exception& error) {
      state.SkipWithError(error.what());
      return;
    }
    state.counters["detector_alone_fps"] = median(alone_fps);
    state.counters["pipeline_fps"] = median(pipeline_fps);
    state.counters["ratio_median"] = median(ratios);
    state.counters["ratio_min"] = *std::min_element(ratios.begin(), ratios.end());
    state.counters["ratio_max"] = *std::max_element(ratios.begin(), ratios.end());
    state.counters["opencv_threads"] = cv::getNumThreads();
  }
}
BENCHMARK(BM_PipelineVsDetectorPaired)
    ->ArgName("threads")
    ->Arg(0)
    ->Arg(1)
    ->Arg(2)
    ->Iterations(1)
    ->Unit(benchmark::kSecond)
    ->UseRealTime();

void BM_MultiSourceEveryFrame(benchmark::State& state) {
  const int sources = static_cast<int>(state.range(0));
  for (auto _ : state) {
    std::unique_ptr<pipeline::Pipeline> run;
    try {
      run = vtest_pipeline(pipeline::PlaybackMode::every_frame, 2, 60, sources);
    } catch (const std::exception& error) {
      state.SkipWithError(error.what());
      return;
    }
    const std::atomic<bool> stop{false};
    const pipeline::PipelineReport report = run->run(stop);
    state.counters["aggregate_fps"] = report.fps;
    state.counters["per_source_fps"] = report.fps / sources;
    state.counters["detector_fps"] = report.detector_fps;
    state.counters["ratio"] = report.detector_fps > 0.0 ? report.fps / report.detector_fps : 0.0;
    state.counters["mean_batch"] =
        report.detector_batches > 0
            ? static_cast<double>(report.frames_processed) / report.detector_batches
            : 0.0;
    state.counters["detect_ms_per_image"] =
        report.detector_fps > 0.0 ? 1000.0 / report.detector_fps : 0.0;
    state.counters["e2e_p50_ms"] =
        ms(report.latency.of(pipeline::Stage::end_to_end).quantile_ns(0.5));
    state.counters["e2e_p99_ms"] =
        ms(report.latency.of(pipeline::Stage::end_to_end).quantile_ns(0.99));
  }
}
BENCHMARK(BM_MultiSourceEveryFrame)
    ->ArgName("sources")
    ->Arg(1)
    ->Arg(2)
    ->Arg(4)
    ->Iterations(1)
    ->Unit(benchmark::kSecond)
    ->UseRealTime();

}  // namespace
