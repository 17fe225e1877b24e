// Tracker throughput on the MOT15 training detections. All 11 sequences are parsed into memory
// first; the timed loop is Tracker::update only. Counter "fps" is frames per second (Hz).
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "motio/frame_detections.hpp"
#include "motio/mot_files.hpp"
#include "tracker/linear_assignment.hpp"
#include "tracker/presets.hpp"
#include "tracker/tracker.hpp"

namespace {
using rtmot::tracker::AffinityKind;
using rtmot::tracker::PredictorKind;
using rtmot::tracker::Tracker;
using rtmot::tracker::TrackerConfig;

struct Sequence {
  rtmot::motio::SequenceInfo info;
  std::vector<std::vector<rtmot::tracker::Detection>> frames;
};

std::filesystem::path shared_dir() {
  if (const char* env = std::getenv("RTMOT_SHARED_DIR")) return env;
  return RTMOT_SHARED_DIR;
}

std::vector<Sequence> load_all() {
  static const char* const kNames[] = {
      "ADL-Rundle-6", "ADL-Rundle-8", "ETH-Bahnhof", "ETH-Pedcross2",  "ETH-Sunnyday", "KITTI-13",
      "KITTI-17",     "PETS09-S2L1",  "TUD-Campus",  "TUD-Stadtmitte", "Venice-2"};
  std::vector<Sequence> sequences;
  for (const char* name : kNames) {
    const auto dir = shared_dir() / "data" / "mot15-train" / name;
    Sequence sequence;
    sequence.info = rtmot::motio::read_seqinfo(dir / "seqinfo.ini");
    const auto rows =
        rtmot::motio::read_mot_file(dir / "det" / "det.txt", rtmot::motio::MotFileKind::detections);
    const rtmot::motio::FrameDetections by_frame(rows);
    for (int frame = 1; frame <= sequence.info.length; ++frame) {
      sequence.frames.push_back(by_frame.at(frame));
    }
    sequences.push_back(std::move(sequence));
  }
  return sequences;
}

// Parsed once, before the first benchmark runs, and read-only afterwards.
const std::vector<Sequence>& mot15() {
  static const std::vector<Sequence> sequences = load_all();
  return sequences;
}

void track_all(benchmark::State& state, const TrackerConfig& base) {
  const auto& sequences = mot15();
  std::vector<Tracker> trackers;
  long frames_per_pass = 0;
  for (const Sequence& sequence : sequences) {
    TrackerConfig config = base;
    config.image_width = static_cast<float>(sequence.info.width);
    config.image_height = static_cast<float>(sequence.info.height);
    config.frame_rate = sequence.info.frame_rate;
    trackers.emplace_back(config);
    frames_per_pass += static_cast<long>(sequence.frames.size());
  }
  long reported = 0;
  for (auto _ : state) {
    for (std::size_t s = 0; s < sequences.size(); ++s) {
      Tracker& tracker = trackers[s];
      tracker.reset();
      const auto& frames = sequences[s].frames;
      const double period = 1.0 / sequences[s].info.frame_rate;
      for (std::size_t f = 0; f < frames.size(); ++f) {
        reported += static_cast<long>(tracker.update(frames[f], f * period).size());
      }
    }
    benchmark::DoNotOptimize(reported);
  }
  state.counters["fps"] = benchmark::Counter(
      static_cast<double>(frames_per_pass) * static_cast<double>(state.iterations()),
      benchmark::Counter::kIsRate);
  state.counters["frames"] = static_cast<double>(frames_per_pass);
}

void BM_SortMot15(benchmark::State& state) {
  track_all(state, TrackerConfig::sort_preset());
}
BENCHMARK(BM_SortMot15)->Unit(benchmark::kMillisecond);

void BM_ModelMot15(benchmark::State& state) {
  TrackerConfig config = TrackerConfig::sort_preset();
  config.predictor = static_cast<PredictorKind>(state.range(0));
  config.affinity = static_cast<AffinityKind>(state.range(1));
  config.affinity_threshold = rtmot::tracker::default_threshold(config.affinity);
  state.SetLabel(std::string(rtmot::tracker::kPredictorNames.name(config.predictor)) + "/" +
                 std::string(rtmot::tracker::kAffinityNames.name(config.affinity)));
  track_all(state, config);
}
// Every predictor with every affinity. (Apply rather than ArgsProduct: Ubuntu 20.04's
// Google Benchmark 1.5.0, on JetPack 5 boards, predates ArgsProduct.)
void every_model(benchmark::internal::Benchmark* bench) {
  for (const auto& predictor : rtmot::tracker::kPredictorNames.entries())
    for (const auto& affinity : rtmot::tracker::kAffinityNames.entries())
      bench->Args({static_cast<int>(predictor.first), static_cast<int>(affinity.first)});
}
BENCHMARK(BM_ModelMot15)->Apply(every_model)->Unit(benchmark::kMillisecond);

void BM_SortAllOptionsMot15(benchmark::State& state) {
  TrackerConfig config = rtmot::tracker::with_every_option(TrackerConfig::sort_preset());
  config.time_step = rtmot::tracker::TimeStep::elapsed;
  track_all(state, config);
}
BENCHMARK(BM_SortAllOptionsMot15)->Unit(benchmark::kMillisecond);

// The default preset: what `rtmot track` and `rtmot run` pay per frame.
void BM_DefaultPresetMot15(benchmark::State& state) {
  track_all(state, *rtmot::tracker::find_preset(rtmot::tracker::default_preset_name()));
}
BENCHMARK(BM_DefaultPresetMot15)->Unit(benchmark::kMillisecond);

// Full-rate output behind a detector 5 frames slow (docs/full-rate.md): the default preset updated
// on every 5th frame and asked for its predictions at the 4 frames between. Counter "fps" counts
// every camera frame (an update or a prediction); "predict_ns" is one prediction's mean cost.
void BM_DefaultPresetFullRateMot15(benchmark::State& state) {
  const auto& sequences = mot15();
  std::vector<Tracker> trackers;
  long frames_per_pass = 0;
  for (const Sequence& sequence : sequences) {
    TrackerConfig config = *rtmot::tracker::find_preset(rtmot::tracker::default_preset_name());
    config.image_width = static_cast<float>(sequence.info.width);
    config.image_height = static_cast<float>(sequence.info.height);
    config.frame_rate = sequence.info.frame_rate;
    trackers.emplace_back(config);
    frames_per_pass += static_cast<long>(sequence.frames.size());
  }
  std::vector<rtmot::tracker::TrackReport> predicted;
  predicted.reserve(1024);
  constexpr std::size_t kEvery = 5;
  long boxes = 0;
  long predictions = 0;
  std::chrono::steady_clock::duration predicting{};
  for (auto _ : state) {
    for (std::size_t s = 0; s < sequences.size(); ++s) {
      Tracker& tracker = trackers[s];
      tracker.reset();
      const auto& frames = sequences[s].frames;
      const double period = 1.0 / sequences[s].info.frame_rate;
      for (std::size_t f = 0; f < frames.size(); ++f) {
        if (f % kEvery == 0) {
          boxes += static_cast<long>(tracker.update(frames[f], f * period).size());
          continue;
        }
        const auto start = std::chrono::steady_clock::now();
        tracker.predict_reported_at(f * period, predicted);
        predicting += std::chrono::steady_clock::now() - start;
        boxes += static_cast<long>(predicted.size());
        ++predictions;
      }
    }
    benchmark::DoNotOptimize(boxes);
  }
  state.counters["fps"] = benchmark::Counter(
      static_cast<double>(frames_per_pass) * static_cast<double>(state.iterations()),
      benchmark::Counter::kIsRate);
  state.counters["predict_ns"] =
      predictions > 0
          ? static_cast<double>(
                std::chrono::duration_cast<std::chrono::nanoseconds>(predicting).count()) /
                static_cast<double>(predictions)
          : 0.0;
}
BENCHMARK(BM_DefaultPresetFullRateMot15)->Unit(benchmark::kMillisecond);

// The assignment alone on a dense square matrix of the given size.
void BM_LinearAssignment(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<double> cost(static_cast<std::size_t>(n) * n);
  for (double& c : cost) c = uniform(rng);
  rtmot::tracker::LinearAssignment solver;
  for (auto _ : state) benchmark::DoNotOptimize(solver.solve(cost.data(), n, n).data());
}
BENCHMARK(BM_LinearAssignment)->Arg(8)->Arg(16)->Arg(64);

}  // namespace
