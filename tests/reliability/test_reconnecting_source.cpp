// ReconnectingSource: backoff arithmetic against a fake clock and scripted sources, then real
// GStreamer test:// sources with injected errors, stalls and end-of-stream.
#include <gtest/gtest.h>

#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "common/input_error.hpp"
#include "platform/reconnecting_source.hpp"

namespace rtmot::platform {
namespace {

using std::chrono::milliseconds;
constexpr std::int64_t ms_ns = 1'000'000;

// A source that plays a script of statuses, then ends.
class ScriptedSource final : public VideoSource {
 public:
  ScriptedSource(std::vector<ReadStatus> script, bool live) : script_(std::move(script)) {
    info_.uri = "scripted";
    info_.live = live;
    info_.fps = 10.0;
    info_.width = 4;
    info_.height = 2;
  }
  ReadStatus read(cv::Mat& bgr, FrameInfo& info) override {
    if (next_ >= script_.size()) return ReadStatus::end_of_stream;
    const ReadStatus status = script_[next_++];
    if (status == ReadStatus::frame) {
      bgr.create(info_.height, info_.width, CV_8UC3);
      ++frames_;
      info.frame_number = frames_;
      info.pts_ns = (frames_ - 1) * 100 * ms_ns;
    }
    return status;
  }
  const SourceInfo& info() const override { return info_; }
  std::string last_error() const override { return "scripted failure"; }

 private:
  std::vector<ReadStatus> script_;
  std::size_t next_{0};
  std::int64_t frames_{0};
  SourceInfo info_;
};

// Time that moves only when the code under test sleeps.
struct FakeTime {
  std::int64_t now{0};
  ReconnectClock clock() {
    return {[this] { return now; }, [this](std::int64_t ns) { now += ns; }};
  }
};

// Opens scripted sources in turn; an empty script stands for "the camera is not there".
struct ScriptedFactory {
  std::deque<std::vector<ReadStatus>> opens;
  bool live{true};
  FakeTime* time{nullptr};
  std::vector<std::int64_t> attempt_times;

  ReconnectingSource::Factory factory() {
    return [this]() -> std::unique_ptr<VideoSource> {
      attempt_times.push_back(time->now);
      if (opens.empty())
        throw InputError("test://gone", 0, "", "no device", ExitCode::source_failed);
      auto script = opens.front();
      opens.pop_front();
      if (script.empty())
        throw InputError("test://gone", 0, "", "no device", ExitCode::source_failed);
      return std::make_unique<ScriptedSource>(script, live);
    };
  }
};

constexpr auto F = ReadStatus::frame;
constexpr auto E = ReadStatus::error;
constexpr auto EOS = ReadStatus::end_of_stream;

TEST(ReconnectingSource, PassesAFilesEndThroughWithoutReopening) {
  FakeTime time;
  ScriptedFactory factory{{{F, F}}, /*live=*/false, &time, {}};
  ReconnectingSource source(factory.factory(), {}, time.clock());
  cv::Mat frame;
  FrameInfo info;
  EXPECT_EQ(source.read(frame, info), F);
  EXPECT_EQ(source.read(frame, info), F);
  EXPECT_EQ(source.read(frame, info), EOS);
  EXPECT_EQ(source.stats().outages, 0);
  EXPECT_EQ(factory.attempt_times.size(), 1U);
}

TEST(ReconnectingSource, FirstOpenFailureIsAnError) {
  FakeTime time;
  ScriptedFactory factory{{{}}, true, &time, {}};
  try {
    ReconnectingSource source(factory.factory(), {}, time.clock());
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_EQ(error.exit_code(), ExitCode::source_failed);
  }
}

TEST(ReconnectingSource, ReportsOutagePromptlyAndContinuesNumbering) {
  FakeTime time;
  ScriptedFactory factory{{{F, F, E}, {F, F}}, true, &time, {}};
  ReconnectPolicy policy;  // 100 ms initial, 100 ms poll
  ReconnectingSource source(factory.factory(), policy, time.clock());
  cv::Mat frame;
  FrameInfo info;
  ASSERT_EQ(source.read(frame, info), F);
  ASSERT_EQ(source.read(frame, info), F);
  EXPECT_EQ(info.frame_number, 2);
  const std::int64_t pts_before = info.pts_ns;

  const std::int64_t outage_start = time.now;
  EXPECT_EQ(source.read(frame, info), E);  // the failure itself: no waiting
  EXPECT_EQ(time.now, outage_start);
  EXPECT_TRUE(source.disconnected());
  EXPECT_NE(source.last_error().find("reconnecting"), std::string::npos) << source.last_error();
  EXPECT_EQ(source.stats().outages, 1);

  // 100 ms later the reopen happens within the next read.
  ASSERT_EQ(source.read(frame, info), F);
  EXPECT_EQ(factory.attempt_times.back(), outage_start + 100 * ms_ns);
  EXPECT_FALSE(source.disconnected());
  EXPECT_EQ(source.stats().reconnects, 1);
  // 100 ms at 10 fps = 1 frame lost, so the first frame after the outage is number 2 + 1 + 1.
  EXPECT_EQ(source.stats().frames_lost, 1);
  EXPECT_EQ(info.frame_number, 4);
  EXPECT_GT(info.pts_ns, pts_before);
}

TEST(ReconnectingSource, BackoffDoublesUpToTheCapAndResetsAfterAFrame) {
  FakeTime time;
  // Connected, fails; then 7 failed reopens; then one that works, which fails again later.
  ScriptedFactory factory{{{F, E}, {}, {}, {}, {}, {}, {}, {}, {F, E}, {F}}, true, &time, {}};
  ReconnectPolicy policy{milliseconds(100), milliseconds(1000), milliseconds(50)};
  ReconnectingSource source(factory.factory(), policy, time.clock());
  cv::Mat frame;
  FrameInfo info;
  ASSERT_EQ(source.read(frame, info), F);
  ASSERT_EQ(source.read(frame, info), E);
  int reads_while_down = 0;
  while (source.read(frame, info) != F) {
    ++reads_while_down;
    ASSERT_LT(reads_while_down, 1000);
  }
  // Attempts (after the first open at 0): gaps 100, 200, 400, 800, 1000, 1000, 1000, 1000 ms.
  ASSERT_EQ(factory.attempt_times.size(), 9U);
  const std::vector<std::int64_t> expected_gaps = {100, 200, 400, 800, 1000, 1000, 1000, 1000};
  for (std::size_t i = 0; i < expected_gaps.size(); ++i) {
    EXPECT_EQ(factory.attempt_times[i + 1] - factory.attempt_times[i], expected_gaps[i] * ms_ns)
        << "gap before attempt " << i + 1;
  }
  EXPECT_EQ(source.stats().failed_attempts, 7);
  // Never blocked longer than one poll interval: 5500 ms of outage in 50 ms ticks.
  EXPECT_GE(reads_while_down, 5500 / 50 - 1);

  // After a delivered frame the next outage starts again at the initial delay.
  ASSERT_EQ(source.read(frame, info), E);
  const std::int64_t second_outage = time.now;
  while (source.read(frame, info) != F) {
  }
  EXPECT_EQ(factory.attempt_times.back() - second_outage, 100 * ms_ns);
  EXPECT_EQ(source.stats().outages, 2);
  EXPECT_EQ(source.stats().reconnects, 2);
}

// Real GStreamer sources with injected faults. Each outage is followed by a reopen that delivers.
void expect_recovers_from(const std::string& uri, int read_timeout_ms) {
  SourceOptions options;
  options.read_timeout_ms = read_timeout_ms;
  options.open_timeout_ms = 3000;
  ReconnectPolicy policy{milliseconds(20), milliseconds(200), milliseconds(20)};
  ReconnectingSource source([&] { return open_video_source(uri, options); }, policy);
  ASSERT_TRUE(source.info().live) << uri;
  cv::Mat frame;
  FrameInfo info;
  std::int64_t last_frame = 0;
  std::int64_t last_pts = -1;
  int frames = 0;
  int errors = 0;
  while (source.stats().reconnects < 2 || frames < 20) {
    const ReadStatus status = source.read(frame, info);
    ASSERT_NE(status, ReadStatus::end_of_stream) << uri;
    if (status == ReadStatus::error) {
      ++errors;
      EXPECT_NE(source.last_error().find("reconnecting"), std::string::npos) << source.last_error();
      ASSERT_LT(errors, 500) << uri << ": never reconnected: " << source.last_error();
      continue;
    }
    ++frames;
    ASSERT_FALSE(frame.empty());
    EXPECT_GT(info.frame_number, last_frame);
    EXPECT_GT(info.pts_ns, last_pts);
    last_frame = info.frame_number;
    last_pts = info.pts_ns;
  }
  EXPECT_GE(source.stats().outages, 2);
  EXPECT_GE(errors, 2);
}

TEST(ReconnectingSourceGst, RecoversFromInjectedErrors) {
  expect_recovers_from("test://ball?is-live=true&width=64&height=48&fps=60&error-after=5", 2000);
}

TEST(ReconnectingSourceGst, RecoversFromAStallPastTheReadTimeout) {
  expect_recovers_from(
      "test://ball?is-live=true&width=64&height=48&fps=60&stall-after=5&stall-ms=1500", 200);
}

TEST(ReconnectingSourceGst, RecoversFromEndOfStream) {
  expect_recovers_from("test://ball?is-live=true&width=64&height=48&fps=60&eos-after=5", 2000);
}

}  // namespace
}  // namespace rtmot::platform
