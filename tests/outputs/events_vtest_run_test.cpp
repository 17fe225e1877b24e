// Issue 24's recorded run: `rtmot run` on vtest.avi with the real SSD, two lines and a zone, every
// frame. The events reach three receivers by three roads, and they must agree: `rtmot listen
// --mqtt` subscribed to the run's MQTT JSON (through Debian's mosquitto, started here), `rtmot
// listen
// --read` on the run's binary file, and the run's Prometheus endpoint, scraped after the last
// frame (output.metrics_linger_s keeps it up). The stream's last message ends it: the tracks still
// inside the zone leave it, and the occupancy is 0.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <csignal>
#include <fstream>
#include <map>
#include <regex>
#include <string>
#include <thread>

#include "child_process.hpp"
#include "metrics_scrape.hpp"
#include "mosquitto_broker.hpp"
#include "scratch_folder.hpp"
#include "shared_data.hpp"

namespace rtmot::outputs {
namespace {

using namespace std::chrono_literals;

constexpr int frames = 300;

// "kind index" -> count, from `rtmot listen`'s summary ("  stream 0: events line_in 0: 3").
std::map<std::string, int> listened_events(const std::string& summary) {
  std::map<std::string, int> counts;
  const std::regex event(R"(stream 0: events (\w+) (\d+): (\d+))");
  for (auto it = std::sregex_iterator(summary.begin(), summary.end(), event);
       it != std::sregex_iterator(); ++it)
    counts[(*it)[1].str() + " " + (*it)[2].str()] = std::stoi((*it)[3]);
  return counts;
}

bool wait_for_text(const std::filesystem::path& file, const std::string& text,
                   std::chrono::seconds limit) {
  const auto deadline = std::chrono::steady_clock::now() + limit;
  while (test::read_text(file).find(text) == std::string::npos) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(50ms);
  }
  return true;
}

class EventsVtestRun : public ::testing::Test {
 protected:
  test::ScratchFolder scratch_{"events-vtest"};  // removed when the test passed
  std::filesystem::path folder_ = scratch_.path();
  std::filesystem::path model_ = test::source_path("models/ssdlite_mobilenet_v2_coco.onnx");
  std::filesystem::path video_ = test::shared_path("data/video/vtest.avi");
};

TEST_F(EventsVtestRun, ListenMqttAndMetricsAgree) {
  RTMOT_REQUIRE_FILE(model_);
  RTMOT_REQUIRE_FILE(video_);
  const test::MosquittoBroker broker(folder_ / "broker");
  test::ChildProcess mqtt_listener({RTMOT_BINARY, "listen", "--mqtt", broker.mqtt_uri("rtmot/cam"),
                                    "--quiet", "--stats-every", "0"},
                                   folder_ / "mqtt.out", folder_ / "mqtt.err");
  ASSERT_TRUE(wait_for_text(folder_ / "mqtt.err", "subscribed to", 20s))
      << test::read_text(folder_ / "mqtt.err");

  // configs/events-demo.yaml's lines and zone. Tiles off: every frame would be 7 SSD passes, and
  // the subject is the events' three roads (tiles: detector_video_tests).
  const auto config = folder_ / "run.yaml";
  std::ofstream(config)
      << "source:\n  uri: " << video_.string() << R"(
  events:
    dwell_s: 3
    lines:
      - {name: middle, units: fraction, from: [0.5, 0.25], to: [0.5, 1.0]}
      - {name: low, units: fraction, from: [0.0, 0.8], to: [1.0, 0.8]}
    zones:
      - {name: left, units: fraction, points: [[0.05, 0.45], [0.4, 0.45], [0.4, 0.95], [0.05, 0.95]]}
playback:
  mode: every-frame
detector:
  kind: ssd
  model: )"
      << model_.string()
      << "\n  score_threshold: 0.5\n  classes: [1]\n  tiles: off\ntracker:\n  preset: rtmot\n";
  const unsigned short metrics_port = test::free_tcp_port();
  const auto binary = folder_ / "m.bin";
  test::ChildProcess run(
      {RTMOT_BINARY, "run", "--config", config.string(), "--max-frames", std::to_string(frames),
       "--binary", binary.string(), "--mqtt", broker.mqtt_uri("rtmot/cam") + "?format=json",
       "--metrics-port", std::to_string(metrics_port), "--metrics-linger", "300"},
      folder_ / "run.out", folder_ / "run.err");
  ASSERT_TRUE(wait_for_text(folder_ / "run.err", "metrics: the final values served", 540s))
      << test::read_text(folder_ / "run.err");
  const std::string metrics = test::http_get(metrics_port, "/metrics");
  const int run_status = run.stop(SIGTERM, 20s);
  ASSERT_TRUE(WIFEXITED(run_status) && WEXITSTATUS(run_status) == 0)
      << run_status << "\n"
      << test::read_text(folder_ / "run.err");
  EXPECT_NE(test::read_text(folder_ / "run.err").find("output mqtt: delivered 301 of 301"),
            std::string::npos)
      << test::read_text(folder_ / "run.err");

  std::this_thread::sleep_for(1s);  // the last messages reach the listener
  const int listen_status = mqtt_listener.stop(SIGTERM, 20s);
  EXPECT_TRUE(WIFEXITED(listen_status) && WEXITSTATUS(listen_status) == 0) << listen_status;
  const std::string from_mqtt = test::read_text(folder_ / "mqtt.out");
  test::ChildProcess reader({RTMOT_BINARY, "listen", "--read", binary.string()},
                            folder_ / "read.out", folder_ / "read.err");
  const int read_status = reader.wait(60s);
  EXPECT_TRUE(WIFEXITED(read_status) && WEXITSTATUS(read_status) == 0)
      << test::read_text(folder_ / "read.err");
  const std::string from_file = test::read_text(folder_ / "read.out");
  // 300 frames and the end of the stream (its events: the tracks still inside leave the zone).
  EXPECT_NE(from_mqtt.find("stream 0: received 301, lost 0"), std::string::npos) << from_mqtt;
  EXPECT_NE(from_file.find("stream 0: received 301, lost 0"), std::string::npos) << from_file;
  EXPECT_NE(from_file.find("seq 300 frame 300: 0 tracks"), std::string::npos);
  EXPECT_NE(from_file.find("(end of stream)"), std::string::npos);
  EXPECT_EQ(from_file.find("(end of stream)"), from_file.rfind("(end of stream)"));

  auto mqtt_events = listened_events(from_mqtt);
  auto file_events = listened_events(from_file);
  EXPECT_EQ(mqtt_events, file_events) << from_mqtt << "\n" << from_file;
  const auto line = [&](const char* name, const char* direction) {
    return test::value_of(metrics, std::string(R"(rtmot_line_crossings_total{stream="0",line=")") +
                                       name + "\",direction=\"" + direction + "\"}");
  };
  const auto zone = [&](const char* event) {
    return test::value_of(
        metrics,
        std::string(R"(rtmot_zone_events_total{stream="0",zone="left",event=")") + event + "\"}");
  };
  EXPECT_EQ(line("middle", "in"), file_events["line_in 0"]);
  EXPECT_EQ(line("middle", "out"), file_events["line_out 0"]);
  EXPECT_EQ(line("low", "in"), file_events["line_in 1"]);
  EXPECT_EQ(line("low", "out"), file_events["line_out 1"]);
  EXPECT_EQ(zone("enter"), file_events["zone_enter 0"]);
  EXPECT_EQ(zone("exit"), file_events["zone_exit 0"]);
  EXPECT_EQ(zone("dwell"), file_events["zone_dwell 0"]);
  EXPECT_EQ(test::value_of(metrics, R"(rtmot_zone_occupancy{stream="0",zone="left"})"),
            file_events["zone_enter 0"] - file_events["zone_exit 0"]);
  EXPECT_EQ(file_events["zone_enter 0"], file_events["zone_exit 0"]);  // nobody left inside
  // The end of the stream is no processed frame.
  EXPECT_EQ(test::value_of(metrics, R"(rtmot_frames_processed_total{stream="0"})"), frames);
  // People walk across the middle line and through the zone in these 30 s of video.
  EXPECT_GT(file_events["line_in 0"] + file_events["line_out 0"], 0) << from_file;
  EXPECT_GT(file_events["zone_enter 0"], 0) << from_file;
  for (const auto& [kind, count] : file_events)
    std::cout << "events " << kind << ": " << count << "\n";
}

}  // namespace
}  // namespace rtmot::outputs
