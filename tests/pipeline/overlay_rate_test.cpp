// The overlay's "fps" (SinkFrame::recent_fps) is the pipeline's recent rate, whatever the log
// interval says. With stats_interval_s 0 (no log line) it used to be counted over an interval that
// never ended, so a run that slowed down kept showing its whole-run mean (pipeline/sink_stage.cpp).
// A real run: vtest.avi, every frame processed, a detector that is fast for the first frames and
// then takes 200 ms a frame (a camera scene that got busy, a throttled board).
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <thread>
#include <vector>

#include "common/frame_rate.hpp"
#include "pipeline/pipeline.hpp"
#include "pipeline_test_parts.hpp"

namespace rtmot::pipeline {
namespace {

using namespace test_parts;

constexpr std::int64_t kFastFrames = 120;
constexpr std::int64_t kSlowFrames = 16;  // 3.2 s at 200 ms: the last 1 s window is all slow
constexpr auto kSlowFrameTime = std::chrono::milliseconds(200);

class SlowingDetector : public detector::Detector {
 public:
  void detect(const cv::Mat& image, std::int64_t frame_number,
              std::vector<tracker::Detection>& out) override {
    if (frame_number > kFastFrames) std::this_thread::sleep_for(kSlowFrameTime);
    boxes_.detect(image, frame_number, out);
  }
  std::string describe() const override { return "fast, then 200 ms a frame"; }

 private:
  FixedBoxDetector boxes_;
};

struct Shown {
  std::int64_t sent_ns;
  double fps;
};

class OverlayRateProbe : public FrameConsumer {
 public:
  explicit OverlayRateProbe(std::vector<Shown>& shown) : shown_(shown) {}
  void consume(const SinkFrame& frame) override {
    if (!frame.result.source_outage)
      shown_.push_back({frame.result.times.sent_ns, frame.recent_fps});
  }
  void finish() override {}

 private:
  std::vector<Shown>& shown_;
};

TEST(OverlayRate, WithTheLogOffItShowsTheRecentRateNotTheRunsMean) {
  std::vector<Shown> shown;
  shown.reserve(kFastFrames + kSlowFrames);
  std::vector<PipelineInput> inputs(1);
  inputs[0].source = std::make_unique<FileSource>(vtest_path());
  inputs[0].tracker = sort_for(10.0);
  std::vector<std::unique_ptr<FrameConsumer>> consumers;
  consumers.push_back(std::make_unique<OverlayRateProbe>(shown));
  PipelineOptions options = quiet(PlaybackMode::every_frame);  // stats_interval_s 0: no log line
  ASSERT_EQ(options.stats_interval_s, 0.0);
  options.max_frames = kFastFrames + kSlowFrames;
  Pipeline pipeline(std::move(inputs), std::make_unique<SlowingDetector>(), std::move(consumers),
                    options);
  const std::atomic<bool> stop{false};
  pipeline.run(stop);
  ASSERT_EQ(static_cast<std::int64_t>(shown.size()), kFastFrames + kSlowFrames);

  // The rates as the frames were actually sent (a loaded machine only stretches the slow phase).
  const Shown& first = shown.front();
  const Shown& last = shown.back();
  const double run_mean =
      frames_per_second(static_cast<std::int64_t>(shown.size()) - 1, last.sent_ns - first.sent_ns);
  const Shown& slow_start = shown[static_cast<std::size_t>(kFastFrames + 4)];
  const double slow_rate = frames_per_second(kSlowFrames - 5, last.sent_ns - slow_start.sent_ns);
  ASSERT_GT(run_mean, 3.0 * slow_rate) << "the fast phase was not fast: nothing to tell apart";

  // While the run was fast the overlay said so; at the end it shows the slow rate (about 5 fps),
  // not the mean of the whole run.
  double fastest_shown = 0.0;
  for (const Shown& s : shown) fastest_shown = std::max(fastest_shown, s.fps);
  EXPECT_GT(fastest_shown, 2.0 * slow_rate);
  EXPECT_GT(last.fps, 0.5 * slow_rate) << "slow rate " << slow_rate << ", run mean " << run_mean;
  EXPECT_LT(last.fps, 1.5 * slow_rate) << "slow rate " << slow_rate << ", run mean " << run_mean;
}

}  // namespace
}  // namespace rtmot::pipeline
