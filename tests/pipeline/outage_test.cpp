// A live source that fails mid-run: the pipeline reopens it with backoff and keeps running and
// sending messages (flagged source_outage, with coasting tracks and so no reports) while it is
// down; the report counts the outages. Faults are injected with GStreamer
// (test://...&error-after=N).
#include <gtest/gtest.h>

#include <atomic>

#include "pipeline/pipeline.hpp"
#include "runner/source_factory.hpp"
#include "tracker/tracker_config.hpp"

namespace rtmot::pipeline {
namespace {

// One person walking slowly right, on every frame that has a picture. Slow and large, so that even
// a long outage (a loaded machine, qemu: reopens that back off for seconds) leaves the coasted box
// overlapping the next detection: the test is about the outage, not about the predictor.
class WalkerDetector : public detector::Detector {
 public:
  void detect(const cv::Mat& image, std::int64_t frame_number,
              std::vector<tracker::Detection>& out) override {
    EXPECT_FALSE(image.empty()) << "the detector must never see an outage tick";
    out.clear();
    out.push_back({{10.F + 0.1F * static_cast<float>(frame_number), 10.F, 24.F, 48.F}, 0.9F, 1});
  }
  std::string describe() const override { return "walker"; }
};

class CollectingSink : public messages::TrackSink {
 public:
  explicit CollectingSink(std::vector<messages::FrameResult>& into) : into_(into) {}
  void write(const messages::FrameResult& result) override { into_.push_back(result); }
  void flush() override {}

 private:
  std::vector<messages::FrameResult>& into_;
};

TEST(SourceOutage, LiveSourceIsReopenedWhileMessagesKeepFlowing) {
  // Every connection delivers 15 frames, then the source posts an error.
  const std::string uri = "test://ball?is-live=true&width=64&height=48&fps=50&error-after=15";
  platform::SourceOptions source_options;
  source_options.open_timeout_ms = 3000;
  auto source = runner::open_source(uri, source_options);

  std::vector<messages::FrameResult> messages;
  std::vector<std::unique_ptr<messages::TrackSink>> sinks;
  sinks.push_back(std::make_unique<CollectingSink>(messages));
  tracker::TrackerConfig tracker_config = tracker::TrackerConfig::sort_preset();
  tracker_config.time_step = tracker::TimeStep::elapsed;
  tracker_config.frame_rate = 50.0;
  tracker_config.max_age = 1000;  // keep the walker alive across outages
  PipelineOptions options;
  options.max_frames = 60;  // four connections' worth
  options.stats_interval_s = 0.0;
  Pipeline pipeline(std::move(source), std::make_unique<WalkerDetector>(), tracker_config,
                    std::move(sinks), options);
  const std::atomic<bool> stop{false};
  const PipelineReport report = pipeline.run(stop);

  EXPECT_GE(report.source_outages, 3);
  EXPECT_TRUE(report.source_error.empty()) << report.source_error;
  EXPECT_EQ(report.frames_captured, 60);

  long ticks = 0;
  long reported_after_first_outage = 0;
  for (std::size_t i = 0; i < messages.size(); ++i) {
    const messages::FrameResult& message = messages[i];
    EXPECT_EQ(message.sequence, i) << "one message per frame or tick, none missing";
    if (message.source_outage) {
      ++ticks;
      EXPECT_TRUE(message.tracks.empty());
    } else if (ticks > 0 && !message.tracks.empty()) {
      ++reported_after_first_outage;
    }
    // The walker keeps its id through every outage (its track coasts): no second id, ever.
    for (const tracker::TrackReport& track : message.tracks)
      EXPECT_EQ(track.id, 1) << "message " << i;
    if (i > 0) {
      EXPECT_GE(message.pts_ns, messages[i - 1].pts_ns) << "time never runs backwards";
    }
  }
  EXPECT_GT(ticks, 0) << "messages kept flowing during the outages";
  // Not the last message: the run may end on the first frame after a reopen, which SORT does not
  // report yet (min_hits counts again after a gap).
  EXPECT_GT(reported_after_first_outage, 0) << "frames flow, and are tracked, after a reopen";
}

}  // namespace
}  // namespace rtmot::pipeline
