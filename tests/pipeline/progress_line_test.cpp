// The periodic line of a one-source run: the sink stage writes it (pipeline/progress_line.hpp), the
// one owner of the interval's rate and percentiles (before, `rtmot run` turned the engine's line
// off for one source and computed the same numbers again in a sink of its own).
#include "pipeline/progress_line.hpp"

#include <gtest/gtest.h>
#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "pipeline/pipeline.hpp"
#include "pipeline_test_parts.hpp"

namespace rtmot::pipeline {
namespace {

using namespace test_parts;

TEST(ProgressLine, SaysWhereTheRunIsAndWhenItEnds) {
  EXPECT_EQ(progress_line(312, 795, 36.24, 30.0, 55.12, 80.0, 312, 0),
            "frame 312 of 795 (39%) | 36.2 fps | capture->sent p50 55.1 ms p95 80.0 ms | "
            "processed 312 skipped 0 | ETA 0:16");
  // A live source has no length: no percentage, no ETA.
  EXPECT_EQ(progress_line(40, 0, 9.96, 10.0, 101.0, 120.0, 38, 2),
            "frame 40 | 10.0 fps | capture->sent p50 101.0 ms p95 120.0 ms | processed 38 "
            "skipped 2");
}

// Every line the default logger writes while alive, message text only.
class LogLines {
 public:
  LogLines() : sink_(std::make_shared<spdlog::sinks::ostream_sink_mt>(text_)) {
    sink_->set_pattern("%v");
    spdlog::default_logger()->sinks().push_back(sink_);
  }
  ~LogLines() {
    auto& sinks = spdlog::default_logger()->sinks();
    sinks.erase(std::remove(sinks.begin(), sinks.end(), sink_), sinks.end());
  }
  LogLines(const LogLines&) = delete;
  LogLines& operator=(const LogLines&) = delete;
  std::vector<std::string> lines() {
    spdlog::default_logger()->flush();
    std::vector<std::string> lines;
    std::istringstream in(text_.str());
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
  }

 private:
  std::ostringstream text_;
  std::shared_ptr<spdlog::sinks::ostream_sink_mt> sink_;
};

class SteadyDetector : public detector::Detector {
 public:
  void detect(const cv::Mat& image, std::int64_t frame_number,
              std::vector<tracker::Detection>& out) override {
    std::this_thread::sleep_for(std::chrono::milliseconds(60));
    boxes_.detect(image, frame_number, out);
  }
  std::string describe() const override { return "fixed boxes, 60 ms a frame"; }

 private:
  FixedBoxDetector boxes_;
};

TEST(ProgressLine, OneSourceRunLogsItEveryInterval) {
  LogLines log;
  std::vector<PipelineInput> inputs(1);
  inputs[0].source = std::make_unique<FileSource>(vtest_path());
  inputs[0].tracker = sort_for(10.0);
  PipelineOptions options = quiet(PlaybackMode::every_frame);
  options.stats_interval_s = 0.5;
  options.max_frames = 24;  // 795 frames in the file: the run's end is --max-frames
  Pipeline pipeline(std::move(inputs), std::make_unique<SteadyDetector>(), {}, options);
  const std::atomic<bool> stop{false};
  pipeline.run(stop);

  const std::regex progress(
      R"(frame (\d+) of 24 \((\d+)%\) \| ([0-9.]+) fps \| capture->sent p50 ([0-9.]+) ms p95 )"
      R"(([0-9.]+) ms \| processed (\d+) skipped 0( \| ETA \d+:\d\d)?)");
  int lines = 0;
  for (const std::string& line : log.lines()) {
    std::smatch m;
    if (!std::regex_match(line, m, progress)) continue;
    ++lines;
    SCOPED_TRACE(line);
    const int frame = std::stoi(m[1]);
    EXPECT_EQ(std::stol(m[2]), std::lround(100.0 * frame / 24));
    EXPECT_GT(std::stod(m[3]), 0.0);
    EXPECT_LE(std::stod(m[4]), std::stod(m[5]));  // p50 <= p95
    EXPECT_EQ(std::stoi(m[6]), frame);            // every frame: all processed so far
    EXPECT_TRUE(m[7].matched);                    // a length and a pace: an ETA
  }
  // 24 frames at 60 ms or more each: at least 1.4 s, so two lines at least.
  EXPECT_GE(lines, 2);
}

}  // namespace
}  // namespace rtmot::pipeline
