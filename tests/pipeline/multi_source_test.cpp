// Several sources through one batched detector: each source keeps its own frames, tracker, stream
// id and accounting; a source that fails or goes silent does not stop or hold back the others.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <map>
#include <mutex>
#include <thread>

#include "outputs/report_json.hpp"
#include "pipeline/pipeline.hpp"
#include "pipeline_test_parts.hpp"

namespace rtmot::pipeline {
namespace {

using namespace test_parts;

// Keeps every message, per stream id; callable from the sink thread while the test watches.
struct PerStream {
  std::mutex mutex;  // the test thread reads while the sink thread writes (test only)
  std::map<std::uint32_t, std::vector<messages::FrameResult>> results;
  int finishes{0};

  std::size_t count(std::uint32_t stream) {
    const std::lock_guard<std::mutex> lock(mutex);
    return results[stream].size();
  }
  std::int64_t last_frame(std::uint32_t stream) {
    const std::lock_guard<std::mutex> lock(mutex);
    const auto& list = results[stream];
    return list.empty() ? 0 : list.back().frame_number;
  }
};

class PerStreamConsumer : public FrameConsumer {
 public:
  explicit PerStreamConsumer(PerStream& into) : into_(into) {}
  void consume(const SinkFrame& frame) override {
    const std::lock_guard<std::mutex> lock(into_.mutex);
    into_.results[frame.result.stream_id].push_back(frame.result);
  }
  void finish() override { ++into_.finishes; }

 private:
  PerStream& into_;
};

std::vector<std::unique_ptr<FrameConsumer>> consumers_into(PerStream& into) {
  std::vector<std::unique_ptr<FrameConsumer>> consumers;
  consumers.push_back(std::make_unique<PerStreamConsumer>(into));
  return consumers;
}

PipelineInput input(std::unique_ptr<platform::VideoSource> source, std::uint32_t stream_id,
                    double fps) {
  PipelineInput in;
  in.source = std::move(source);
  in.tracker = sort_for(fps);
  in.stream_id = stream_id;
  return in;
}

void expect_frames_in_order(const std::vector<messages::FrameResult>& results, std::int64_t last) {
  ASSERT_FALSE(results.empty());
  for (std::size_t i = 0; i < results.size(); ++i) {
    EXPECT_EQ(results[i].sequence, i);
    if (i > 0) {
      EXPECT_LT(results[i - 1].frame_number, results[i].frame_number);
    }
  }
  EXPECT_EQ(results.back().frame_number, last);
}

// FixedBoxDetector that records the size of every batch it is given.
class BatchRecordingDetector : public FixedBoxDetector {
 public:
  explicit BatchRecordingDetector(std::vector<int>& sizes) : sizes_(sizes) {}
  void detect_batch(const cv::Mat* const* images, const std::int64_t* frame_numbers, int count,
                    std::vector<std::vector<tracker::Detection>>& out) override {
    sizes_.push_back(count);
    FixedBoxDetector::detect_batch(images, frame_numbers, count, out);
  }
  int max_batch() const override { return 8; }

 private:
  std::vector<int>& sizes_;
};

TEST(MultiSource, TwoRecordingsEveryFrameKeepTheirOwnStreamsTrackersAndCounts) {
  RTMOT_REQUIRE_FILE(vtest_path());
  PerStream seen;
  std::vector<PipelineInput> inputs;
  inputs.push_back(input(std::make_unique<FileSource>(vtest_path()), 7, 10.0));
  inputs.push_back(input(std::make_unique<FileSource>(vtest_path()), 9, 10.0));
  auto options = quiet(PlaybackMode::every_frame);
  options.max_frames = 40;
  Pipeline pipeline(std::move(inputs), std::make_unique<FixedBoxDetector>(), consumers_into(seen),
                    options);
  const std::atomic<bool> stop{false};
  const PipelineReport report = pipeline.run(stop);

  ASSERT_EQ(seen.results.size(), 2U) << "two stream ids, no other";
  for (const std::uint32_t id : {7U, 9U}) {
    const auto& results = seen.results[id];
    ASSERT_EQ(results.size(), 40U) << "stream " << id;
    expect_frames_in_order(results, 40);
    for (const auto& result : results) EXPECT_EQ(result.frames_dropped, 0U);
  }
  // Same pictures, same boxes, separate trackers: both streams get the same track ids (a shared
  // tracker would give the second stream new ids or merge the boxes).
  for (std::size_t i = 0; i < 40; ++i) {
    const auto& a = seen.results[7][i].tracks;
    const auto& b = seen.results[9][i].tracks;
    ASSERT_EQ(a.size(), b.size()) << "frame " << i + 1;
    for (std::size_t t = 0; t < a.size(); ++t) EXPECT_EQ(a[t].id, b[t].id);
  }
  EXPECT_EQ(seen.finishes, 1);
  EXPECT_EQ(report.frames_captured, 80);
  EXPECT_EQ(report.frames_processed, 80);
  ASSERT_EQ(report.streams.size(), 2U);
  for (const StreamReport& stream : report.streams) {
    EXPECT_EQ(stream.frames_captured, 40);
    EXPECT_EQ(stream.frames_processed, 40);
    EXPECT_EQ(stream.frames_dropped, 0);
    EXPECT_EQ(stream.latency.of(pipeline::Stage::end_to_end).count(), 40);
    EXPECT_GT(stream.fps, 0.0);
  }
  EXPECT_EQ(report.streams[0].stream_id, 7U);
  EXPECT_EQ(report.streams[1].stream_id, 9U);
  EXPECT_LE(report.detector_batches, 80) << "at most one batch per frame";
  EXPECT_GE(report.detector_batches, 40) << "a batch holds at most one frame per source";
  const auto json = outputs::to_json(report);
  ASSERT_EQ(json["streams"].size(), 2U);
  EXPECT_EQ(json["streams"][1]["stream_id"], 9);
  EXPECT_EQ(json["streams"][1]["frames"]["processed"], 40);
}

// A recording whose decoder fails after `good` frames.
class FailingFileSource : public FileSource {
 public:
  FailingFileSource(const std::string& path, std::int64_t good) : FileSource(path), good_(good) {}
  ReadStatus read(cv::Mat& bgr, FrameInfo& info) override {
    if (++reads_ > good_) return ReadStatus::error;
    return FileSource::read(bgr, info);
  }
  std::string last_error() const override { return "decoder broke"; }

 private:
  std::int64_t good_;
  std::int64_t reads_{0};
};

TEST(MultiSource, ASourceThatFailsEndsAloneAndIsReportedOnItsStream) {
  RTMOT_REQUIRE_FILE(vtest_path());
  PerStream seen;
  std::vector<PipelineInput> inputs;
  inputs.push_back(input(std::make_unique<FailingFileSource>(vtest_path(), 10), 0, 10.0));
  inputs.push_back(input(std::make_unique<FileSource>(vtest_path()), 1, 10.0));
  auto options = quiet(PlaybackMode::every_frame);
  options.max_frames = 60;
  Pipeline pipeline(std::move(inputs), std::make_unique<FixedBoxDetector>(), consumers_into(seen),
                    options);
  const std::atomic<bool> stop{false};
  const PipelineReport report = pipeline.run(stop);
  expect_frames_in_order(seen.results[0], 10);
  expect_frames_in_order(seen.results[1], 60);
  ASSERT_EQ(report.streams.size(), 2U);
  EXPECT_EQ(report.streams[0].source_error, "decoder broke");
  EXPECT_EQ(report.streams[0].frames_processed, 10);
  EXPECT_TRUE(report.streams[1].source_error.empty());
  EXPECT_EQ(report.streams[1].frames_processed, 60);
  EXPECT_EQ(report.source_error, "decoder broke");
}

// A live camera that goes down after 10 frames for `outage_reads` reads (reconnecting), then
// comes back for 10 more frames.
class FlakyCamera : public PatternSource {
 public:
  explicit FlakyCamera(int outage_reads) : PatternSource(20), outage_reads_(outage_reads) {}
  ReadStatus read(cv::Mat& bgr, FrameInfo& info) override {
    if (frames_ == 10 && down_ < outage_reads_) {
      ++down_;
      reconnecting_ = true;
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      return ReadStatus::error;
    }
    reconnecting_ = false;
    const ReadStatus status = PatternSource::read(bgr, info);
    if (status == ReadStatus::frame) ++frames_;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    return status;
  }
  bool reconnecting() const override { return reconnecting_; }
  std::string last_error() const override { return "camera unplugged"; }

 private:
  int outage_reads_;
  int down_{0};
  int frames_{0};
  bool reconnecting_{false};
};

TEST(MultiSource, ACameraOutageIsReportedOnItsStreamWhileTheOthersRunOn) {
  PerStream seen;
  std::vector<PipelineInput> inputs;
  inputs.push_back(input(std::make_unique<PatternSource>(300), 0, 1000.0));
  inputs.push_back(input(std::make_unique<FlakyCamera>(30), 1, 1000.0));
  Pipeline pipeline(std::move(inputs), std::make_unique<FixedBoxDetector>(), consumers_into(seen),
                    quiet(PlaybackMode::realtime));
  const std::atomic<bool> stop{false};
  const PipelineReport report = pipeline.run(stop);
  std::size_t ticks = 0;
  for (const auto& result : seen.results[1]) {
    if (result.source_outage) {
      ++ticks;
      EXPECT_TRUE(result.tracks.empty());
    }
  }
  EXPECT_GT(ticks, 0U) << "the outage reaches the ground station on stream 1";
  EXPECT_EQ(seen.results[1].back().frame_number, 20) << "the camera came back";
  for (const auto& result : seen.results[0]) EXPECT_FALSE(result.source_outage);
  EXPECT_EQ(seen.results[0].back().frame_number, 300) << "stream 0 ran to its end";
  ASSERT_EQ(report.streams.size(), 2U);
  EXPECT_EQ(report.streams[0].source_outages, 0);
  EXPECT_EQ(report.streams[1].source_outages, 1);
}

// A live camera that never delivers a frame until the run is stopped.
class SilentCamera : public platform::VideoSource {
 public:
  explicit SilentCamera(const std::atomic<bool>& stop) : stop_(stop) {
    info_.uri = "silent://";
    info_.live = true;
    info_.fps = 30.0;
  }
  ReadStatus read(cv::Mat&, FrameInfo&) override {
    while (!stop_.load()) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    return ReadStatus::end_of_stream;
  }
  const platform::SourceInfo& info() const override { return info_; }
  std::string last_error() const override { return {}; }

 private:
  const std::atomic<bool>& stop_;
  platform::SourceInfo info_;
};

TEST(MultiSource, ASilentCameraDoesNotHoldBackTheOthersBatches) {
  PerStream seen;
  std::atomic<bool> stop{false};
  std::vector<PipelineInput> inputs;
  inputs.push_back(input(std::make_unique<SilentCamera>(stop), 0, 30.0));
  inputs.push_back(input(std::make_unique<PatternSource>(200), 1, 1000.0));
  auto options = quiet(PlaybackMode::realtime);
  options.batch_wait = std::chrono::milliseconds(5);
  Pipeline pipeline(std::move(inputs), std::make_unique<FixedBoxDetector>(), consumers_into(seen),
                    options);
  std::thread stopper([&] {
    // If the detector waited for the silent camera, frame 200 would never come out and this test
    // would end by ctest's timeout.
    while (seen.last_frame(1) != 200) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    stop = true;
  });
  const PipelineReport report = pipeline.run(stop);
  stopper.join();
  EXPECT_EQ(seen.count(0), 0U);
  EXPECT_EQ(seen.results[1].back().frame_number, 200);
  EXPECT_EQ(report.streams[1].frames_captured, 200);
}

TEST(MultiSource, AnnotatedVideoWithSeveralSourcesIsRefused) {
  std::vector<PipelineInput> inputs;
  inputs.push_back(input(std::make_unique<PatternSource>(1), 0, 30.0));
  inputs.push_back(input(std::make_unique<PatternSource>(1), 1, 30.0));
  auto options = quiet(PlaybackMode::realtime);
  options.keep_images = true;  // what an annotated video asks for
  EXPECT_THROW(Pipeline(std::move(inputs), std::make_unique<FixedBoxDetector>(), {}, options),
               std::invalid_argument);
}

}  // namespace
}  // namespace rtmot::pipeline
