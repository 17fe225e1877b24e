// The pipeline end to end with test detectors: the playback modes on vtest.avi (simulated: exactly
// the predicted frames, deterministic tracks), image-less MOT sequences, a fast live source under
// random delays, stop and failure handling.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <future>
#include <opencv2/core.hpp>
#include <random>
#include <set>
#include <thread>

#include "common/input_error.hpp"
#include "motio/frame_detections.hpp"
#include "motio/mot_files.hpp"
#include "outputs/report_json.hpp"
#include "pipeline/pipeline.hpp"
#include "pipeline_test_parts.hpp"
#include "platform/clock.hpp"
#include "runner/sequence_clock_source.hpp"
#include "shared_data.hpp"
#include "tracker/tracker_config.hpp"

namespace rtmot::pipeline {
namespace {

using namespace test_parts;
using platform::FrameInfo;
using platform::ReadStatus;

PipelineReport run_vtest(PlaybackMode mode, Collected& collected, std::int64_t max_frames = 0) {
  auto options = quiet(mode);
  options.simulated_latency_ms = 250.0;
  options.max_frames = max_frames;
  Pipeline pipeline(std::make_unique<FileSource>(vtest_path()),
                    std::make_unique<FixedBoxDetector>(), sort_for(10.0), sinks_into(collected),
                    options);
  const std::atomic<bool> stop{false};
  return pipeline.run(stop);
}

std::vector<std::int64_t> frame_numbers(const Collected& collected) {
  std::vector<std::int64_t> numbers;
  for (const auto& result : collected.results) numbers.push_back(result.frame_number);
  return numbers;
}

TEST(SimulatedPlayback, VtestAt250msProcessesExactlyThePredictedFramesDeterministically) {
  RTMOT_REQUIRE_FILE(vtest_path());
  // 10 fps (frames 100 ms apart) and a detector busy 250 ms per frame: free at virtual time t, it
  // takes the newest frame with pts <= t (or waits for the next one). Predicted here independently
  // of SimulatedClock: pts 0, 200, 500, 700, 1000, ... plus the stream's last frame.
  const int frame_count = 795;
  std::vector<std::int64_t> predicted;
  {
    std::int64_t free_at_ms = 0;
    int next_index = 0;  // frames before it were taken or skipped
    while (next_index < frame_count) {
      const std::int64_t look_ms = std::max<std::int64_t>(free_at_ms, next_index * 100);
      int newest = next_index;
      while (newest + 1 < frame_count && (newest + 1) * 100 <= look_ms) ++newest;
      predicted.push_back(newest + 1);
      free_at_ms = look_ms + 250;
      next_index = newest + 1;
    }
  }

  Collected first;
  const PipelineReport report = run_vtest(PlaybackMode::simulated, first);
  EXPECT_EQ(report.frames_captured, frame_count);
  EXPECT_EQ(frame_numbers(first), predicted);
  EXPECT_EQ(report.frames_processed, static_cast<std::int64_t>(predicted.size()));
  EXPECT_EQ(report.frames_dropped, frame_count - static_cast<std::int64_t>(predicted.size()));
  // About 4 of every 10 frames at 4 detections per second on a 10 fps video.
  EXPECT_EQ(std::count_if(predicted.begin(), predicted.end(), [](auto n) { return n <= 100; }), 40);
  ASSERT_FALSE(first.results.empty());
  const messages::FrameResult& last = first.results.back();
  EXPECT_EQ(last.frames_dropped, last.frame_number - 1 - static_cast<std::int64_t>(last.sequence));
  EXPECT_EQ(first.flushes, 1);
  for (std::size_t i = 0; i < first.results.size(); ++i) {
    EXPECT_EQ(first.results[i].sequence, i);
    EXPECT_EQ(first.results[i].pts_ns, (first.results[i].frame_number - 1) * 100'000'000);
  }
  std::size_t frames_with_tracks = 0;
  for (const auto& result : first.results) frames_with_tracks += result.tracks.empty() ? 0 : 1;
  EXPECT_GT(frames_with_tracks, first.results.size() / 2) << "the tracker must see the boxes";

  Collected second;
  run_vtest(PlaybackMode::simulated, second);
  ASSERT_EQ(first.results.size(), second.results.size());
  for (std::size_t i = 0; i < first.results.size(); ++i) {
    const auto& a = first.results[i].tracks;
    const auto& b = second.results[i].tracks;
    ASSERT_EQ(a.size(), b.size()) << "frame " << first.results[i].frame_number;
    for (std::size_t t = 0; t < a.size(); ++t) {
      EXPECT_EQ(a[t].id, b[t].id);
      EXPECT_EQ(a[t].box.x, b[t].box.x);
      EXPECT_EQ(a[t].box.y, b[t].box.y);
      EXPECT_EQ(a[t].box.w, b[t].box.w);
      EXPECT_EQ(a[t].box.h, b[t].box.h);
    }
  }
}

TEST(EveryFramePlayback, ProcessesEveryFrameInOrderWithAllLatencyPoints) {
  RTMOT_REQUIRE_FILE(vtest_path());
  Collected collected;
  const PipelineReport report = run_vtest(PlaybackMode::every_frame, collected, 120);
  EXPECT_EQ(report.frames_captured, 120);
  EXPECT_EQ(report.frames_processed, 120);
  EXPECT_EQ(report.frames_dropped, 0);
  ASSERT_EQ(collected.results.size(), 120U);
  for (std::size_t i = 0; i < collected.results.size(); ++i) {
    const messages::FrameResult& result = collected.results[i];
    EXPECT_EQ(result.frame_number, static_cast<std::int64_t>(i) + 1);
    EXPECT_EQ(result.frames_dropped, 0U);
    const messages::FrameTimes& t = result.times;
    EXPECT_GT(t.captured_ns, 0);
    EXPECT_LE(t.captured_ns, t.detect_start_ns);
    EXPECT_LE(t.detect_start_ns, t.detected_ns);
    EXPECT_LE(t.detected_ns, t.tracked_ns);
    EXPECT_LE(t.tracked_ns, t.sent_ns);
  }
  EXPECT_EQ(report.latency.of(pipeline::Stage::end_to_end).count(), 120);
  EXPECT_GT(report.fps, 0.0);
  // The detector is busy for part of the wall time only, so its own rate is at least the
  // pipeline's.
  EXPECT_GE(report.detector_fps, report.fps);
  const auto json = outputs::to_json(report);
  EXPECT_EQ(json["frames"]["processed"], 120);
  EXPECT_TRUE(json["latency"]["end_to_end"].contains("p99_ms"));
  // The stages as the Prometheus metrics name them (one table: pipeline::kStageNames).
  for (const char* stage : {"queue", "detect", "track", "sink", "end_to_end"}) {
    EXPECT_EQ(json["latency"][stage]["count"], 120) << stage;
  }
}

TEST(SequencePlayback, ImageLessMotSequenceFeedsItsDetectionsFrameByFrame) {
  const auto sequence = test::shared_path("data/mot15-train/ADL-Rundle-6");
  RTMOT_REQUIRE_FILE(sequence / "seqinfo.ini");
  RTMOT_REQUIRE_FILE(sequence / "det/det.txt");
  const motio::SequenceInfo info = motio::read_seqinfo(sequence / "seqinfo.ini");
  const motio::FrameDetections by_frame(
      motio::read_mot_file(sequence / "det/det.txt", motio::MotFileKind::detections));

  // Hands out det.txt's boxes by frame number and checks that no image came with them.
  class DetFileDetector : public detector::Detector {
   public:
    explicit DetFileDetector(const motio::FrameDetections& by_frame) : by_frame_(by_frame) {}
    void detect(const cv::Mat& image, std::int64_t frame_number,
                std::vector<tracker::Detection>& out) override {
      EXPECT_TRUE(image.empty());
      out = by_frame_.at(frame_number);
    }
    std::string describe() const override { return "det.txt"; }

   private:
    const motio::FrameDetections& by_frame_;
  };

  Collected collected;
  Pipeline pipeline(std::make_unique<runner::SequenceClockSource>("mot-seq://" + sequence.string()),
                    std::make_unique<DetFileDetector>(by_frame), sort_for(info.frame_rate),
                    sinks_into(collected), quiet(PlaybackMode::every_frame));
  const std::atomic<bool> stop{false};
  const PipelineReport report = pipeline.run(stop);
  EXPECT_EQ(report.frames_processed, info.length);
  ASSERT_EQ(collected.results.size(), static_cast<std::size_t>(info.length));
  EXPECT_EQ(collected.results[30].pts_ns, std::llround(30 * 1e9 / info.frame_rate));
  std::set<std::int32_t> ids;
  for (const auto& result : collected.results) {
    for (const auto& track : result.tracks) ids.insert(track.id);
  }
  EXPECT_GT(ids.size(), 5U) << "SORT on ADL-Rundle-6's detections finds many people";
}

TEST(SequencePlayback, MissingSeqinfoNamesTheFile) {
  try {
    runner::SequenceClockSource source("mot-seq:///nonexistent/sequence");
    FAIL() << "expected an InputError";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("seqinfo.ini"), std::string::npos) << error.what();
  }
}

// Verifies that the image is the frame it claims to be, at random speeds.
class CheckingDetector : public detector::Detector {
 public:
  explicit CheckingDetector(std::atomic<int>& torn) : torn_(torn) {}
  void detect(const cv::Mat& image, std::int64_t frame_number,
              std::vector<tracker::Detection>& out) override {
    const auto expected = static_cast<unsigned char>(frame_number % 251);
    if (cv::countNonZero(image.reshape(1) != expected) != 0) ++torn_;
    out.clear();
    out.push_back({{10.F, 10.F, 5.F, 5.F}, 0.9F, 1});
    if (std::uniform_int_distribution<int>(0, 9)(random_) == 0) {
      std::this_thread::sleep_for(std::chrono::microseconds(500));
    }
  }
  std::string describe() const override { return "checking"; }

 private:
  std::atomic<int>& torn_;
  std::mt19937 random_{5};
};

TEST(LivePipeline, LatestFrameUnderRandomDelaysNeverTearsRepeatsOrReorders) {
  std::atomic<int> torn{0};
  Collected collected;
  auto options = quiet(PlaybackMode::every_frame);  // ignored: a live source takes the latest
  options.keep_images = false;
  Pipeline pipeline(std::make_unique<PatternSource>(4000), std::make_unique<CheckingDetector>(torn),
                    sort_for(1000.0), sinks_into(collected), options);
  const std::atomic<bool> stop{false};
  const PipelineReport report = pipeline.run(stop);
  EXPECT_EQ(torn.load(), 0);
  EXPECT_EQ(report.frames_captured, 4000);
  EXPECT_EQ(report.frames_processed + report.frames_dropped, 4000);
  ASSERT_FALSE(collected.results.empty());
  EXPECT_EQ(collected.results.back().frame_number, 4000) << "the last frame survives shutdown";
  for (std::size_t i = 1; i < collected.results.size(); ++i) {
    ASSERT_LT(collected.results[i - 1].frame_number, collected.results[i].frame_number);
    const auto& r = collected.results[i];
    EXPECT_EQ(r.frames_dropped, static_cast<std::uint32_t>(r.frame_number - 1 - i));
  }
}

TEST(LivePipeline, StopFlagEndsTheRunAndFlushesTheSinks) {
  std::atomic<int> torn{0};
  Collected collected;
  Pipeline pipeline(std::make_unique<PatternSource>(1'000'000'000),
                    std::make_unique<CheckingDetector>(torn), sort_for(1000.0),
                    sinks_into(collected), quiet(PlaybackMode::realtime));
  std::atomic<bool> stop{false};
  std::thread stopper([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    stop = true;
  });
  const PipelineReport report = pipeline.run(stop);
  stopper.join();
  EXPECT_LT(report.frames_captured, 1'000'000'000);
  EXPECT_EQ(static_cast<std::int64_t>(collected.results.size()), report.frames_processed);
  EXPECT_EQ(collected.flushes, 1);
}

// A recording whose second frame is stamped an hour after its first (a gap in the recording, or
// a hostile file). Played in real time the run waits for that hour; a stop must still end it now.
class HourGapRecording : public platform::VideoSource {
 public:
  HourGapRecording() {
    info_.uri = "hour-gap://";
    info_.fps = 10.0;
  }
  ReadStatus read(cv::Mat& bgr, FrameInfo& info) override {
    if (next_ > 2) return ReadStatus::end_of_stream;
    bgr.create(24, 32, CV_8UC3);
    bgr.setTo(cv::Scalar::all(0));
    info.frame_number = next_;
    info.pts_ns = next_ == 1 ? 0 : 3600LL * 1'000'000'000;
    info.capture_ns = platform::steady_now_ns();
    ++next_;
    return ReadStatus::frame;
  }
  const platform::SourceInfo& info() const override { return info_; }
  std::string last_error() const override { return {}; }

 private:
  std::int64_t next_{1};
  platform::SourceInfo info_;
};

TEST(RealtimePlayback, AStopEndsTheWaitForAFarTimestamp) {
  Collected collected;
  Pipeline pipeline(std::make_unique<HourGapRecording>(), std::make_unique<FixedBoxDetector>(),
                    sort_for(10.0), sinks_into(collected), quiet(PlaybackMode::realtime));
  std::atomic<bool> stop{false};
  std::thread stopper([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    stop = true;
  });
  auto finished = std::async(std::launch::async, [&] { return pipeline.run(stop); });
  const bool ended = finished.wait_for(std::chrono::seconds(60)) == std::future_status::ready;
  stopper.join();
  if (!ended) {
    // The capture thread still sleeps towards the second frame: nothing left to do but say so.
    ADD_FAILURE() << "the run ignored the stop while waiting for a timestamp an hour away";
    std::_Exit(1);
  }
  const PipelineReport report = finished.get();
  EXPECT_EQ(report.frames_processed, 1);  // the first frame; the second was read, never due
  EXPECT_EQ(static_cast<std::int64_t>(collected.results.size()), report.frames_processed);
  EXPECT_EQ(collected.flushes, 1);
}

TEST(LivePipeline, DetectorFailureIsRethrownAfterTheSinksWereFlushed) {
  class FailingDetector : public detector::Detector {
   public:
    void detect(const cv::Mat&, std::int64_t frame_number,
                std::vector<tracker::Detection>& out) override {
      out.clear();
      if (frame_number >= 50) throw std::runtime_error("detector broke");
    }
    std::string describe() const override { return "failing"; }
  };
  RTMOT_REQUIRE_FILE(vtest_path());
  Collected collected;
  Pipeline pipeline(std::make_unique<FileSource>(vtest_path()), std::make_unique<FailingDetector>(),
                    sort_for(10.0), sinks_into(collected), quiet(PlaybackMode::every_frame));
  const std::atomic<bool> stop{false};
  EXPECT_THROW(pipeline.run(stop), std::runtime_error);
  EXPECT_EQ(collected.flushes, 1);
  EXPECT_LE(collected.results.size(), 49U);
}

}  // namespace
}  // namespace rtmot::pipeline
