// The Prometheus endpoint: started on a free loopback port, fed with realistic frames (MOT15
// detections timed as a 30 fps capture, an outage in the middle), scraped over HTTP here.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "child_process.hpp"
#include "common/input_error.hpp"
#include "message_test_data.hpp"
#include "metrics_scrape.hpp"
#include "outputs/metrics_server.hpp"
#include "outputs/pipeline_metrics.hpp"
#include "shared_data.hpp"

namespace rtmot::outputs {
namespace {

using test::connect_to;
using test::http_get;
using test::value_of;

TEST(Metrics, EndpointServesPrometheusText) {
  auto frames = test::frames_from_detections("TUD-Stadtmitte", 120);
  ASSERT_EQ(frames.size(), 120U);
  std::uint64_t sent = 0;
  std::uint64_t dropped = 0;
  PipelineMetrics metrics(
      {OutputProbe{"udp", [&] { return sent; }, [&] { return dropped; }, {}, {}}},
      {frames.front().stream_id});
  const unsigned short port = test::free_tcp_port();
  MetricsServer server(metrics, "127.0.0.1", port);
  EXPECT_EQ(server.url(), "http://127.0.0.1:" + std::to_string(port) + "/metrics");

  MetricsSink sink(metrics);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    auto& frame = frames[i];
    frame.frames_dropped = static_cast<std::uint32_t>(i / 10);
    frame.source_outage = i >= 50 && i < 55;  // one outage, five ticks long
    if (frame.source_outage) frame.tracks.clear();
    ++sent;
    dropped += i % 40 == 0 ? 1 : 0;
    sink.write(frame);
  }
  const std::string response = http_get(port, "/metrics");
  ASSERT_NE(response.find("200 OK"), std::string::npos) << response;
  EXPECT_NE(response.find("Content-Type: text/plain; version=0.0.4"), std::string::npos);
  EXPECT_EQ(value_of(response, R"(rtmot_frames_processed_total{stream="7"})"), 120.0);
  EXPECT_EQ(value_of(response, R"(rtmot_frames_captured_total{stream="7"})"),
            static_cast<double>(frames.back().frame_number));
  EXPECT_EQ(value_of(response, R"(rtmot_frames_skipped_total{stream="7"})"), 11.0);
  EXPECT_EQ(value_of(response, R"(rtmot_source_outages_total{stream="7"})"), 1.0);
  EXPECT_EQ(value_of(response, R"(rtmot_outage_messages_total{stream="7"})"), 5.0);
  EXPECT_EQ(value_of(response, R"(rtmot_source_up{stream="7"})"), 1.0);
  EXPECT_EQ(value_of(response, R"(rtmot_tracks{stream="7"})"),
            static_cast<double>(frames.back().tracks.size()));
  std::size_t tracks = 0;
  for (const auto& frame : frames) tracks += frame.tracks.size();
  EXPECT_EQ(value_of(response, R"(rtmot_tracks_reported_total{stream="7"})"),
            static_cast<double>(tracks));
  EXPECT_NE(response.find("rtmot_build_info{version=\""), std::string::npos);
  EXPECT_EQ(value_of(response, R"(rtmot_output_messages_total{output="udp",outcome="sent"})"),
            120.0);
  EXPECT_EQ(value_of(response, R"(rtmot_output_messages_total{output="udp",outcome="dropped"})"),
            3.0);
  // Every processed frame that was not an outage tick is in each stage's histogram; buckets are
  // cumulative and end with +Inf = count.
  EXPECT_EQ(value_of(response, R"(rtmot_stage_latency_seconds_count{stage="end_to_end"})"), 115.0);
  EXPECT_EQ(value_of(response, R"(rtmot_stage_latency_seconds_bucket{stage="detect",le="+Inf"})"),
            115.0);
  EXPECT_LE(value_of(response, R"(rtmot_stage_latency_seconds_bucket{stage="detect",le="0.001"})"),
            value_of(response, R"(rtmot_stage_latency_seconds_bucket{stage="detect",le="0.1"})"));
  // The report's output rate (pipeline::output_rate): the 115 pictures, not the 5 outage ticks,
  // over first capture -> last picture sent. Counting the ticks as frames read 30.06 here.
  const double span_s =
      static_cast<double>(frames.back().times.sent_ns - frames.front().times.captured_ns) / 1e9;
  EXPECT_NEAR(value_of(response, R"(rtmot_fps{stream="7"})"), 115.0 / span_s, 0.0005);
  EXPECT_NE(http_get(port, "/other").find("404"), std::string::npos);
}

// Full-rate output (docs/full-rate.md): a skipped frame's predicted message is counted apart, not
// as a processed frame, and has no place in the latency histograms. Those whose boxes were followed
// in the image (observed) are counted among them too.
TEST(Metrics, PredictedMessagesAreCountedApart) {
  auto frames = test::frames_from_detections("TUD-Stadtmitte", 40);
  PipelineMetrics metrics({}, {frames.front().stream_id});
  const unsigned short port = test::free_tcp_port();
  MetricsServer server(metrics, "127.0.0.1", port);
  MetricsSink sink(metrics);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    frames[i].predicted = i % 4 != 0;  // a detector 4 frames slow
    // The image followed the boxes on the first two skipped frames after each detection only.
    frames[i].observed = frames[i].predicted && i % 4 != 3;
    sink.write(frames[i]);
  }
  const std::string response = http_get(port, "/metrics");
  EXPECT_EQ(value_of(response, R"(rtmot_frames_processed_total{stream="7"})"), 10.0);
  EXPECT_EQ(value_of(response, R"(rtmot_predicted_messages_total{stream="7"})"), 30.0);
  EXPECT_EQ(value_of(response, R"(rtmot_observed_messages_total{stream="7"})"), 20.0);
  EXPECT_EQ(value_of(response, R"(rtmot_stage_latency_seconds_count{stage="end_to_end"})"), 10.0);
  // The page's per-source capture->sent: one source, so the pipeline's own (the same frames).
  const nlohmann::json status = metrics.status();
  const nlohmann::json& source = status["sources"][0]["end_to_end"];
  EXPECT_GT(source["p50_ms"].get<double>(), 0.0);
  EXPECT_EQ(source["p50_ms"], status["latency"]["end_to_end"]["p50_ms"]);
  EXPECT_EQ(source["p99_ms"], status["latency"]["end_to_end"]["p99_ms"]);
}

// Issue 23, class 4: one connection that sends nothing, and 50 that send half a request and then
// nothing, held open while Prometheus scrapes: every scrape is answered within its 10 s timeout.
// With civetweb's defaults (one worker, 30 s request timeout) the first scrape got nothing.
TEST(Metrics, ScrapesAreAnsweredWhileIdleAndHalfSentConnectionsAreHeld) {
  auto frames = test::frames_from_detections("TUD-Stadtmitte", 10);
  PipelineMetrics metrics({}, {frames.front().stream_id});
  MetricsSink sink(metrics);
  for (auto& frame : frames) sink.write(frame);
  const unsigned short port = test::free_tcp_port();
  MetricsServer server(metrics, "127.0.0.1", port);

  std::vector<int> held;
  held.push_back(connect_to(port));  // idle: sends nothing
  for (int i = 0; i < 50; ++i) {
    const int fd = connect_to(port);
    const std::string half = "GET /metrics HTTP/1.1\r\nHost: loc";
    (void)!::write(fd, half.data(), half.size());
    held.push_back(fd);
  }
  for (const int fd : held) ASSERT_GE(fd, 0) << "a held connection was refused";
  for (int scrape = 0; scrape < 3; ++scrape) {
    const std::string response = http_get(port, "/metrics");
    ASSERT_NE(response.find("200 OK"), std::string::npos)
        << "scrape " << scrape << ": " << response;
    EXPECT_EQ(value_of(response, "rtmot_frames_processed_total{stream=\"" +
                                     std::to_string(frames.front().stream_id) + "\"}"),
              10.0);
  }
  for (const int fd : held) ::close(fd);
}

// Two sources through one pipeline: each has its own series (the captured count was one stream's,
// below the processed count of both); a source down is 0 in rtmot_source_up, the other stays 1.
TEST(Metrics, EverySourceHasItsOwnSeries) {
  const auto frames = test::frames_from_detections("TUD-Stadtmitte", 60);
  PipelineMetrics metrics({}, {5, 6});
  for (const auto& recorded : frames) {
    for (const std::uint32_t stream : {5U, 6U}) {
      auto frame = recorded;
      frame.stream_id = stream;
      frame.frame_number = recorded.frame_number * (stream == 5 ? 1 : 2);  // 6 skips every other
      frame.frames_dropped = stream == 5 ? 0 : static_cast<std::uint32_t>(recorded.frame_number);
      frame.source_outage = stream == 6 && &recorded == &frames.back();
      metrics.observe(frame);
    }
  }
  const std::string text = metrics.render();
  const double last = static_cast<double>(frames.back().frame_number);
  EXPECT_EQ(value_of(text, R"(rtmot_frames_captured_total{stream="5"})"), last);
  EXPECT_EQ(value_of(text, R"(rtmot_frames_captured_total{stream="6"})"), 2 * last);
  EXPECT_EQ(value_of(text, R"(rtmot_frames_processed_total{stream="5"})"), 60.0);
  EXPECT_EQ(value_of(text, R"(rtmot_frames_processed_total{stream="6"})"), 60.0);
  EXPECT_EQ(value_of(text, R"(rtmot_frames_skipped_total{stream="6"})"), last);
  EXPECT_EQ(value_of(text, R"(rtmot_source_up{stream="5"})"), 1.0);
  EXPECT_EQ(value_of(text, R"(rtmot_source_up{stream="6"})"), 0.0);
  EXPECT_EQ(value_of(text, R"(rtmot_source_outages_total{stream="6"})"), 1.0);
  // One HELP/TYPE per family, whatever the number of sources (promtool rejects repeats).
  std::size_t type_lines = 0;
  for (std::size_t at = 0;
       (at = text.find("# TYPE rtmot_frames_captured_total ", at)) != std::string::npos; ++at) {
    ++type_lines;
  }
  EXPECT_EQ(type_lines, 1U);
  // The web page's status (docs/web.md) says the same facts.
  const nlohmann::json status = metrics.status();
  ASSERT_EQ(status["sources"].size(), 2U);
  const nlohmann::json& six = status["sources"][1];
  EXPECT_EQ(six["stream"], 6);
  EXPECT_EQ(six["frames_captured"].get<double>(), 2 * last);
  EXPECT_EQ(six["frames_processed"], 60);
  EXPECT_EQ(six["frames_skipped"].get<double>(), last);
  EXPECT_EQ(six["up"], false);
  EXPECT_EQ(status["sources"][0]["up"], true);
  EXPECT_EQ(six["outages"], 1);
  EXPECT_NEAR(status["sources"][0]["fps"].get<double>(), value_of(text, R"(rtmot_fps{stream="5"})"),
              1e-3);
}

// The detector's capacity (the page's health, rtmot_detector_capacity_fps): frames over the union
// of the detector's busy intervals, as the run's report counts it. Frames of one batch share their
// stamps (counted once); a second lane's batch overlapping the first adds only its own part.
TEST(Metrics, DetectorCapacityCountsABatchOnceAndOverlappingLanesAsTheirUnion) {
  auto frames = test::frames_from_detections("TUD-Stadtmitte", 5);
  PipelineMetrics metrics({}, {frames.front().stream_id});
  MetricsSink sink(metrics);
  EXPECT_EQ(metrics.status()["detector_capacity_fps"], 0.0);  // nothing detected yet
  constexpr std::int64_t ms = 1'000'000;
  const std::int64_t t0 = frames.front().times.detect_start_ns;
  // Frames 0 and 1: one batch of 40 ms; 2: a lane from 30 to 70 ms (overlaps by 10); 3: an outage
  // tick (no picture, not detected); 4: 100 to 120 ms. Busy 40 + 30 + 20 = 90 ms for 4 frames.
  const std::int64_t intervals[5][2] = {{0, 40}, {0, 40}, {30, 70}, {70, 70}, {100, 120}};
  for (std::size_t i = 0; i < frames.size(); ++i) {
    frames[i].times.detect_start_ns = t0 + intervals[i][0] * ms;
    frames[i].times.detected_ns = t0 + intervals[i][1] * ms;
    frames[i].source_outage = i == 3;
    sink.write(frames[i]);
  }
  EXPECT_NEAR(metrics.status()["detector_capacity_fps"].get<double>(), 4 / 0.090, 1e-6);
  EXPECT_NEAR(value_of(metrics.render(), "rtmot_detector_capacity_fps"), 4 / 0.090, 1e-3);
}

// The page's p50/p99 are read from the buckets as histogram_quantile does: linear inside the
// bucket that holds the rank.
TEST(Metrics, QuantilesInterpolateInsideTheirBucket) {
  LatencyBuckets buckets;
  EXPECT_EQ(buckets.quantile_ms(0.5), 0.0);                // no frame yet
  for (int i = 0; i < 99; ++i) buckets.record(2'500'000);  // 2.5 ms: the (2, 3] bucket
  buckets.record(400'000'000);                             // 400 ms: (300, 500]
  EXPECT_DOUBLE_EQ(buckets.quantile_ms(0.5), 2.0 + 50.0 / 99.0);
  EXPECT_DOUBLE_EQ(buckets.quantile_ms(0.99), 3.0);
  EXPECT_DOUBLE_EQ(buckets.quantile_ms(1.0), 500.0);
  buckets.record(10'000'000'000);  // 10 s: past the last bound
  EXPECT_DOUBLE_EQ(buckets.quantile_ms(1.0), LatencyBuckets::bounds_ms.back());
}

// The latency buckets are fine where the latencies are: a true p95 of 36.9 ms is bracketed by
// bounds 5 ms apart (35..40 ms), not 20..50 ms; no bucket below 200 ms is wider than a third of
// its upper bound (or 2 ms).
TEST(Metrics, LatencyBucketsAreFineBetweenHalfAMillisecondAnd200) {
  std::size_t fine = 0;
  for (std::size_t i = 1; i < LatencyBuckets::bounds_ms.size(); ++i) {
    const double low = LatencyBuckets::bounds_ms[i - 1];
    const double high = LatencyBuckets::bounds_ms[i];
    if (high <= 200.0) {
      EXPECT_LE(high - low, std::max(2.0, 0.34 * high)) << low << ".." << high;
      ++fine;
    }
  }
  EXPECT_EQ(LatencyBuckets::bounds_ms.front(), 0.5);
  EXPECT_GE(fine, 15U);
  const auto above =
      std::upper_bound(LatencyBuckets::bounds_ms.begin(), LatencyBuckets::bounds_ms.end(), 36.9);
  EXPECT_EQ(*above - *(above - 1), 5.0);
}

TEST(Metrics, PortInUseIsANetworkError) {
  PipelineMetrics metrics({}, {});
  const unsigned short port = test::free_tcp_port();
  MetricsServer first(metrics, "127.0.0.1", port);
  try {
    MetricsServer second(metrics, "127.0.0.1", port);
    FAIL() << "two servers on one port";
  } catch (const InputError& error) {
    EXPECT_EQ(error.exit_code(), ExitCode::network);
  }
}

// After the run the endpoint may linger with the final values (metrics_linger_s): a source that
// failed showed rtmot_source_up 1 there. rtmot itself, a test:// source that fails after 15
// frames, the replay detector; scraped while it lingers.
TEST(Metrics, SourceIsDownWhileTheEndpointLingersAfterTheSourceFailed) {
  const auto det = test::shared_path("data/mot15-train/TUD-Campus/det/det.txt");
  RTMOT_REQUIRE_FILE(det);
  const auto folder = std::filesystem::temp_directory_path() /
                      ("rtmot-metrics-linger-" + std::to_string(::getpid()));
  std::filesystem::create_directories(folder);
  const unsigned short port = test::free_tcp_port();
  test::ChildProcess rtmot(
      {RTMOT_BINARY, "run", "--source", "test://ball?num-buffers=100&error-after=15", "--det-file",
       det.string(), "--metrics-port", std::to_string(port), "--metrics-linger", "300",
       "--stats-interval", "0"},
      folder / "out.txt", folder / "err.txt");
  // Generous: a loaded machine or qemu takes seconds to start the run.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (test::read_text(folder / "err.txt").find("metrics: the final values served") ==
             std::string::npos &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  const std::string text = http_get(port, "/metrics");
  const int status = rtmot.stop(SIGTERM, std::chrono::seconds(30));
  const std::string err = test::read_text(folder / "err.txt");
  EXPECT_NE(err.find("the source failed"), std::string::npos) << err;
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 5) << status << "\n" << err;
  EXPECT_EQ(value_of(text, R"(rtmot_frames_processed_total{stream="0"})"), 15.0) << text;
  EXPECT_EQ(value_of(text, R"(rtmot_source_up{stream="0"})"), 0.0) << text;
  std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace rtmot::outputs
