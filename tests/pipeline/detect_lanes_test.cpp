// Batches in flight (pipeline/detect_stage.hpp, detect_lane.hpp): the detect stage with K lanes,
// each a detector of its own, fed by every-frame sources and read by a consumer, all on their own
// threads (run it under ThreadSanitizer: scripts/sanitize.sh tsan). Checks that every frame of
// every source comes out once, in order, with the detections of its own picture; that lanes run
// at the same time; and that a lane's failure ends the stage with that error after every earlier
// batch was handed on, with every lane joined (no hang). Then whole pipelines on vtest.avi: in
// flight 1 and 2 give the same tracks.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <exception>
#include <map>
#include <memory>
#include <random>
#include <stdexcept>
#include <thread>
#include <vector>

#include "pipeline/detect_stage.hpp"
#include "pipeline/pipeline.hpp"
#include "pipeline_test_parts.hpp"

namespace rtmot::pipeline {
namespace {

using namespace test_parts;

// A frame's picture says which source and which frame it is (a lane that mixed two frames up, or
// a picture overwritten while detected, gives itself away).
void paint(cv::Mat& image, std::size_t input, std::int64_t frame) {
  image.create(6, 8, CV_8UC3);
  image.setTo(cv::Scalar(static_cast<double>(input), static_cast<double>(frame % 256),
                         static_cast<double>(frame / 256)));
}

std::int64_t frame_of(const cv::Mat& image) {
  const cv::Vec3b pixel = image.at<cv::Vec3b>(5, 7);
  return pixel[1] + 256 * static_cast<std::int64_t>(pixel[2]);
}

// What the lanes did, together.
struct LaneLog {
  std::atomic<int> active{0};
  std::atomic<int> most_active{0};
  std::atomic<int> calls{0};
  std::int64_t fail_on_frame{-1};  // a batch with this frame of source 0 throws; -1: none
};

// One box per picture, its x the source and frame the picture shows; sleeps a random while, as a
// forward pass would.
class PictureDetector : public detector::Detector {
 public:
  PictureDetector(LaneLog& log, unsigned seed) : log_(log), random_(seed) {}
  void detect(const cv::Mat& image, std::int64_t frame_number,
              std::vector<tracker::Detection>& out) override {
    EXPECT_EQ(frame_of(image), frame_number % 65536) << "the picture is not the frame's";
    out.clear();
    const cv::Vec3b pixel = image.at<cv::Vec3b>(0, 0);
    out.push_back({{static_cast<float>(pixel[0] * 100000 + frame_number), 1.F, 2.F, 3.F}, 0.9F, 1});
  }
  void detect_batch(const cv::Mat* const* images, const std::int64_t* frame_numbers, int count,
                    std::vector<std::vector<tracker::Detection>>& out) override {
    log_.calls.fetch_add(1);
    const int now = log_.active.fetch_add(1) + 1;
    int most = log_.most_active.load();
    while (now > most && !log_.most_active.compare_exchange_weak(most, now)) {
    }
    std::this_thread::sleep_for(std::chrono::microseconds(delay_(random_)));
    log_.active.fetch_sub(1);
    for (int i = 0; i < count; ++i) {
      if (images[i]->at<cv::Vec3b>(0, 0)[0] == 0 && frame_numbers[i] == log_.fail_on_frame)
        throw std::runtime_error("lane failed on purpose");
    }
    Detector::detect_batch(images, frame_numbers, count, out);
  }
  int max_batch() const override { return 8; }
  std::string describe() const override { return "picture detector"; }

 private:
  LaneLog& log_;
  std::mt19937 random_;
  std::uniform_int_distribution<int> delay_{200, 1500};
};

struct StageRun {
  std::map<std::size_t, std::vector<std::int64_t>> frames;  // per source, as handed on
  std::exception_ptr error;
  DetectCounts counts;
};

// `sources` every-frame producers of `frames` frames each through a stage of `lanes` lanes.
StageRun run_stage(std::size_t sources, std::int64_t frames, int lanes, LaneLog& log) {
  WakeSignal frames_ready;
  std::vector<std::unique_ptr<LatestFrameSlot>> slots;
  std::vector<LatestFrameSlot*> inputs;
  for (std::size_t i = 0; i < sources; ++i) {
    slots.push_back(std::make_unique<LatestFrameSlot>(SlotMode::every_frame, &frames_ready));
    inputs.push_back(slots.back().get());
  }
  std::vector<std::unique_ptr<detector::Detector>> detectors;
  for (int lane = 0; lane < lanes; ++lane) {
    detectors.push_back(std::make_unique<PictureDetector>(log, 17U + static_cast<unsigned>(lane)));
  }
  DetectOptions options;
  options.batch_wait = std::chrono::microseconds(500);
  DetectStage stage(std::move(detectors), inputs, frames_ready, options);
  EXPECT_EQ(stage.lanes(), static_cast<std::size_t>(lanes));

  std::atomic<bool> abort{false};
  std::vector<std::thread> producers;
  for (std::size_t i = 0; i < sources; ++i) {
    producers.emplace_back([&, i] {
      LatestFrameSlot& slot = *slots[i];
      for (std::int64_t f = 1; f <= frames; ++f) {
        paint(slot.back().image, i, f);
        slot.back().info.frame_number = f;
        slot.back().outage = false;
        if (!slot.publish(abort)) break;
      }
      slot.close();
    });
  }
  StageRun result;
  std::thread detect([&] {
    try {
      stage.run(abort);
    } catch (...) {
      result.error = std::current_exception();
      // What the pipeline's RunControl does: abort, so that every wait gives up.
      abort.store(true);
      for (auto& slot : slots) slot->wake_all();
    }
    stage.finish();
  });
  SpscQueue<DetectedFrame>& output = stage.output();
  while (DetectedFrame* item = output.front(abort)) {
    EXPECT_EQ(item->detections.size(), 1U);
    if (item->detections.size() != 1U) {
      output.pop();
      continue;
    }
    EXPECT_EQ(item->detections[0].box.x,
              static_cast<float>(item->input * 100000 +
                                 static_cast<std::size_t>(item->info.frame_number)))
        << "detections of another picture";
    EXPECT_LE(item->times.captured_ns, item->times.detect_start_ns);
    EXPECT_LE(item->times.detect_start_ns, item->times.detected_ns);
    result.frames[item->input].push_back(item->info.frame_number);
    output.pop();
  }
  detect.join();
  for (auto& producer : producers) producer.join();
  result.counts = stage.counts();
  return result;
}

void expect_every_frame_once_in_order(const StageRun& run, std::size_t sources,
                                      std::int64_t frames) {
  ASSERT_EQ(run.frames.size(), sources);
  for (const auto& [input, numbers] : run.frames) {
    ASSERT_EQ(numbers.size(), static_cast<std::size_t>(frames)) << "source " << input;
    for (std::size_t i = 0; i < numbers.size(); ++i) {
      ASSERT_EQ(numbers[i], static_cast<std::int64_t>(i) + 1) << "source " << input;
    }
  }
}

TEST(DetectLanes, OneLaneHandsOnEveryFrameOfEverySourceInOrder) {
  LaneLog log;
  const StageRun run = run_stage(3, 120, 1, log);
  ASSERT_FALSE(run.error);
  expect_every_frame_once_in_order(run, 3, 120);
  EXPECT_EQ(log.most_active.load(), 1);
  EXPECT_EQ(run.counts.frames, 360);
  EXPECT_EQ(run.counts.batches, log.calls.load());
}

TEST(DetectLanes, TwoAndThreeLanesRunAtOnceAndStillHandOnInOrder) {
  for (const int lanes : {2, 3}) {
    SCOPED_TRACE(lanes);
    LaneLog log;
    const StageRun run = run_stage(4, 150, lanes, log);
    ASSERT_FALSE(run.error);
    expect_every_frame_once_in_order(run, 4, 150);
    EXPECT_GE(log.most_active.load(), 2) << "the lanes never overlapped";
    EXPECT_LE(log.most_active.load(), lanes);
    EXPECT_EQ(run.counts.frames, 600);
    EXPECT_EQ(run.counts.batches, log.calls.load());
    EXPECT_GT(run.counts.busy_ns, 0);
  }
}

TEST(DetectLanes, ALaneThatFailsEndsTheStageWithItsErrorAfterEveryEarlierBatch) {
  for (const int lanes : {1, 2}) {
    SCOPED_TRACE(lanes);
    LaneLog log;
    log.fail_on_frame = 10;
    const StageRun run = run_stage(2, 200, lanes, log);
    ASSERT_TRUE(run.error) << "the failure was swallowed";
    try {
      std::rethrow_exception(run.error);
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "lane failed on purpose");
    }
    // Source 0's frames 1..9 were handed on (a batch holds at most one frame per source), none
    // after; the other source's, in order, as far as they got.
    ASSERT_EQ(run.frames.count(0), 1U);
    const std::vector<std::int64_t> first_nine{1, 2, 3, 4, 5, 6, 7, 8, 9};
    EXPECT_EQ(run.frames.at(0), first_nine);
    std::size_t handed_on = 0;
    for (const auto& [input, numbers] : run.frames) {
      for (std::size_t i = 0; i < numbers.size(); ++i) {
        EXPECT_EQ(numbers[i], static_cast<std::int64_t>(i) + 1);
      }
      handed_on += numbers.size();
    }
    EXPECT_EQ(static_cast<std::int64_t>(handed_on), run.counts.frames);
    EXPECT_GE(run.counts.batches, 9);
    EXPECT_LE(handed_on, 40U);
  }
}

// Whole pipelines: two recordings, every frame, through in-flight 1 and 2 give the same tracks.
std::map<std::uint32_t, std::vector<messages::FrameResult>> track_vtest(int lanes) {
  struct Keep : FrameConsumer {
    std::map<std::uint32_t, std::vector<messages::FrameResult>>& into;
    explicit Keep(std::map<std::uint32_t, std::vector<messages::FrameResult>>& i) : into(i) {}
    void consume(const SinkFrame& frame) override {
      into[frame.result.stream_id].push_back(frame.result);
    }
    void finish() override {}
  };
  std::map<std::uint32_t, std::vector<messages::FrameResult>> results;
  std::vector<PipelineInput> inputs;
  for (std::uint32_t id : {3U, 4U}) {
    PipelineInput in;
    in.source = std::make_unique<FileSource>(vtest_path());
    in.tracker = sort_for(10.0);
    in.stream_id = id;
    inputs.push_back(std::move(in));
  }
  std::vector<std::unique_ptr<detector::Detector>> detectors;
  for (int lane = 0; lane < lanes; ++lane)
    detectors.push_back(std::make_unique<FixedBoxDetector>());
  std::vector<std::unique_ptr<FrameConsumer>> consumers;
  consumers.push_back(std::make_unique<Keep>(results));
  auto options = quiet(PlaybackMode::every_frame);
  options.max_frames = 30;
  Pipeline pipeline(std::move(inputs), std::move(detectors), std::move(consumers), options);
  const std::atomic<bool> stop{false};
  const PipelineReport report = pipeline.run(stop);
  EXPECT_EQ(report.frames_processed, 60);
  EXPECT_GT(report.detector_fps, 0.0);
  return results;
}

TEST(DetectLanes, InFlightOneAndTwoGiveTheSameTracksOnARecording) {
  RTMOT_REQUIRE_FILE(vtest_path());
  const auto one = track_vtest(1);
  const auto two = track_vtest(2);
  ASSERT_EQ(one.size(), 2U);
  ASSERT_EQ(two.size(), 2U);
  for (const auto& [id, results] : one) {
    const auto& other = two.at(id);
    ASSERT_EQ(results.size(), 30U);
    ASSERT_EQ(other.size(), 30U);
    for (std::size_t i = 0; i < results.size(); ++i) {
      EXPECT_EQ(results[i].frame_number, other[i].frame_number);
      ASSERT_EQ(results[i].tracks.size(), other[i].tracks.size()) << "frame " << i + 1;
      for (std::size_t t = 0; t < results[i].tracks.size(); ++t) {
        EXPECT_EQ(results[i].tracks[t].id, other[i].tracks[t].id);
        EXPECT_EQ(results[i].tracks[t].box.x, other[i].tracks[t].box.x);
      }
    }
  }
}

}  // namespace
}  // namespace rtmot::pipeline
