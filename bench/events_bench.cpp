// What counting costs next to the tracker stage: 50 people walking across a 1920x1080 frame with
// jittery detections, the rtmot preset tracking them (BM_TrackerStage), and the EventCounter on
// the tracker's reports of the same frames with 5 lines + 5 zones and 10 + 10 (BM_EventCounter).
// Both report time per frame, and BM_EventCounter its share of the tracker's (pct_of_tracker: both
// as this thread's CPU time, so a loaded machine inflates neither; docs/events.md, "Cost"). With
// 0 shapes it shows the per-track work alone.
#include <benchmark/benchmark.h>
#include <time.h>

#include <random>
#include <string>
#include <vector>

#include "events/event_counter.hpp"
#include "tracker/presets.hpp"
#include "tracker/tracker.hpp"

namespace {

using rtmot::tracker::Detection;
using rtmot::tracker::TrackReport;

constexpr int kPeople = 50;
constexpr int kFrames = 3000;
constexpr double kFps = 25.0;

// Deterministic scene: each person walks straight at 1-4 px/frame, wrapping at the borders.
std::vector<std::vector<Detection>> scene() {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> x0(0.0, 1880.0);
  std::uniform_real_distribution<double> y0(0.0, 960.0);
  std::uniform_real_distribution<double> speed(-4.0, 4.0);
  std::normal_distribution<double> jitter(0.0, 2.0);
  struct Person {
    double x, y, vx, vy;
  };
  std::vector<Person> people;
  for (int i = 0; i < kPeople; ++i)
    people.push_back({x0(random), y0(random), speed(random), speed(random) / 3});
  std::vector<std::vector<Detection>> frames(kFrames);
  for (auto& frame : frames) {
    for (auto& p : people) {
      p.x += p.vx;
      p.y += p.vy;
      if (p.x < 0 || p.x > 1880) p.vx = -p.vx;
      if (p.y < 0 || p.y > 960) p.vy = -p.vy;
      Detection d;
      d.box = {static_cast<float>(p.x + jitter(random)), static_cast<float>(p.y + jitter(random)),
               static_cast<float>(40 + jitter(random)), static_cast<float>(110 + jitter(random))};
      d.score = 0.9F;
      d.class_id = 1;
      frame.push_back(d);
    }
  }
  return frames;
}

rtmot::tracker::TrackerConfig tracker_config() {
  auto config = *rtmot::tracker::find_preset("rtmot");
  config.frame_rate = kFps;
  config.image_width = 1920;
  config.image_height = 1080;
  return config;
}

// This thread's CPU time in microseconds.
double thread_cpu_us() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) * 1e6 + static_cast<double>(now.tv_nsec) * 1e-3;
}

// BM_TrackerStage's CPU time per frame, for BM_EventCounter's share (0: not run in this process).
double tracker_cpu_us_per_frame = 0.0;

const std::vector<std::vector<Detection>>& frames() {
  static const auto detections = scene();
  return detections;
}

// The tracker's reports of every frame, recorded once.
const std::vector<std::vector<TrackReport>>& reports() {
  static const auto recorded = [] {
    rtmot::tracker::Tracker tracker(tracker_config());
    std::vector<std::vector<TrackReport>> out;
    for (std::size_t f = 0; f < frames().size(); ++f)
      out.push_back(tracker.update(frames()[f], f / kFps));
    return out;
  }();
  return recorded;
}

void BM_TrackerStage(benchmark::State& state) {
  rtmot::tracker::Tracker tracker(tracker_config());
  std::size_t f = 0;
  double reported = 0;
  const double start = thread_cpu_us();
  for (auto _ : state) {
    const auto& out = tracker.update(frames()[f % kFrames], static_cast<double>(f) / kFps);
    reported += static_cast<double>(out.size());
    benchmark::DoNotOptimize(out.data());
    ++f;
  }
  tracker_cpu_us_per_frame = (thread_cpu_us() - start) / static_cast<double>(f);
  state.counters["tracks_per_frame"] = reported / static_cast<double>(f);
}
BENCHMARK(BM_TrackerStage)->Unit(benchmark::kMicrosecond);

void BM_EventCounter(benchmark::State& state) {
  const int shapes = static_cast<int>(state.range(0));
  rtmot::events::EventsConfig config;
  for (int i = 0; i < shapes; ++i) {
    const double x = 100.0 + 1700.0 * i / shapes;
    config.lines.push_back({"line" + std::to_string(i), {{x, 0.0}, {x + 50.0, 1080.0}}, true});
    const double y = 50.0 + 900.0 * i / shapes;
    // Concave: a U of 8 corners.
    config.zones.push_back({"zone" + std::to_string(i),
                            {{x, y},
                             {x + 60, y},
                             {x + 60, y + 150},
                             {x + 120, y + 150},
                             {x + 120, y},
                             {x + 180, y},
                             {x + 180, y + 200},
                             {x, y + 200}},
                            5.0});
  }
  rtmot::events::EventCounter counter(config);
  const auto& recorded = reports();
  std::size_t f = 0;
  double events = 0;
  const double start = thread_cpu_us();
  for (auto _ : state) {
    // Timestamps keep rising across passes over the recording, so no track looks re-found.
    const auto& out = counter.update(recorded[f % kFrames], static_cast<double>(f) / kFps);
    events += static_cast<double>(out.size());
    ++f;
  }
  const double counter_cpu_us_per_frame = (thread_cpu_us() - start) / static_cast<double>(f);
  if (tracker_cpu_us_per_frame > 0.0)
    state.counters["pct_of_tracker"] = 100.0 * counter_cpu_us_per_frame / tracker_cpu_us_per_frame;
  state.counters["events_per_frame"] = events / static_cast<double>(f);
  state.counters["lines"] = shapes;
  state.counters["zones"] = shapes;
}
BENCHMARK(BM_EventCounter)->Arg(0)->Arg(5)->Arg(10)->Unit(benchmark::kMicrosecond);

}  // namespace
