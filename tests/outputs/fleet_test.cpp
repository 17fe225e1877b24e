// A fleet: 50 simulated boards (threads, each an MqttPublisher with its own stream id, publishing
// MOT15 track messages at a camera's pace) through one mosquitto broker to one `rtmot listen
// --mqtt` process. At QoS 1 nothing is lost; with the broker restarted mid-run the listener counts
// the loss and every board's publishing resumes. The numbers are printed (and recorded as test
// properties) for the report.
#include <gtest/gtest.h>
#include <mosquitto.h>
#include <sys/wait.h>

#include <chrono>
#include <csignal>
#include <fstream>
#include <ostream>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "message_test_data.hpp"
#include "mosquitto_broker.hpp"
#include "outputs/mqtt_publisher.hpp"
#include "scratch_folder.hpp"
#include "shared_data.hpp"

namespace rtmot::outputs {
namespace {

using namespace std::chrono_literals;

constexpr int boards = 50;
constexpr std::size_t messages_per_board = 100;
constexpr auto frame_interval = 20ms;  // 50 fps per board: 2500 messages/s through the broker

struct StreamLine {
  std::uint64_t received{0};
  std::uint64_t lost{0};
  std::uint64_t duplicated{0};
};

struct Summary {
  std::uint64_t messages{0};
  std::uint64_t corrupt{0};
  std::map<std::uint32_t, StreamLine> streams;
};

// Reads `rtmot listen`'s summary (its documented output, docs/message-format.md).
Summary parse_summary(const std::string& out) {
  Summary summary;
  std::smatch match;
  const std::regex total(R"(summary after [0-9.]+ s: (\d+) messages, (\d+) corrupt)");
  if (std::regex_search(out, match, total)) {
    summary.messages = std::stoull(match[1]);
    summary.corrupt = std::stoull(match[2]);
  }
  const std::regex stream(
      R"(stream (\d+): received (\d+), lost (\d+), reordered \d+, duplicated (\d+))");
  for (auto it = std::sregex_iterator(out.begin(), out.end(), stream); it != std::sregex_iterator();
       ++it) {
    StreamLine line;
    line.received = std::stoull((*it)[2]);
    line.lost = std::stoull((*it)[3]);
    line.duplicated = std::stoull((*it)[4]);
    summary.streams[static_cast<std::uint32_t>(std::stoul((*it)[1]))] = line;
  }
  return summary;
}

struct FleetRun {
  std::uint64_t queued{0};
  std::uint64_t dropped{0};
  std::uint64_t published{0};
  std::uint64_t reconnects{0};
  double seconds{0.0};
};

// Every board publishes the same recorded sequence under its own stream id and topic, binary or
// JSON as `format_of(board)` says.
FleetRun run_fleet(
    const test::MosquittoBroker& broker, const std::function<void()>& mid_run,
    const std::function<const char*(int board)>& format_of = [](int) { return "binary"; }) {
  const auto frames = test::frames_from_detections("ETH-Bahnhof", messages_per_board);
  std::vector<std::unique_ptr<MqttPublisher>> publishers;
  for (int board = 0; board < boards; ++board) {
    MqttPublisherOptions options;
    std::string problem;
    options.uri = *parse_mqtt_uri(broker.mqtt_uri("fleet/board" + std::to_string(board) +
                                                  "?qos=1&format=" + format_of(board)),
                                  problem);
    options.client_id = "fleet-board-" + std::to_string(board);
    publishers.push_back(std::make_unique<MqttPublisher>(options, 1000 + board));
  }
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::thread> threads;
  for (int board = 0; board < boards; ++board) {
    threads.emplace_back([&, board] {
      auto next = std::chrono::steady_clock::now();
      for (auto frame : frames) {
        frame.stream_id = 1000 + static_cast<std::uint32_t>(board);
        publishers[static_cast<std::size_t>(board)]->write(frame);
        next += frame_interval;
        std::this_thread::sleep_until(next);
      }
    });
  }
  mid_run();
  for (auto& thread : threads) thread.join();
  FleetRun run;
  for (auto& publisher : publishers) {
    publisher->flush();
    run.queued += publisher->counters().queued.load();
    run.dropped += publisher->counters().dropped.load();
    run.published += publisher->counters().published.load();
    run.reconnects += publisher->counters().connects.load() - 1;
  }
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return run;
}

class Fleet : public ::testing::Test {
 protected:
  test::ScratchFolder scratch_{"fleet"};  // removed when the test passed
  std::filesystem::path folder_ = scratch_.path();

  std::unique_ptr<test::ChildProcess> start_listener(const test::MosquittoBroker& broker,
                                                     const std::string& filter = "fleet/#") {
    auto listener = std::make_unique<test::ChildProcess>(
        std::vector<std::string>{RTMOT_BINARY, "listen", "--mqtt", broker.mqtt_uri(filter),
                                 "--quiet", "--stats-every", "0"},
        folder_ / "listen.out", folder_ / "listen.err");
    // Listening once its subscription is acknowledged (it logs that line).
    const auto deadline = std::chrono::steady_clock::now() + 20s;
    while (test::read_text(folder_ / "listen.err").find("subscribed to") == std::string::npos &&
           std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(20ms);
    }
    EXPECT_NE(test::read_text(folder_ / "listen.err").find("subscribed to"), std::string::npos)
        << test::read_text(folder_ / "listen.err");
    return listener;
  }

  Summary stop_listener(std::unique_ptr<test::ChildProcess> listener) {
    std::this_thread::sleep_for(1s);  // the last messages reach the listener
    const int status = listener->stop(SIGTERM, 20s);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status;
    return parse_summary(test::read_text(folder_ / "listen.out"));
  }

  void report(const char* name, const FleetRun& run, const Summary& summary) {
    std::uint64_t lost = 0;
    std::uint64_t duplicated = 0;
    for (const auto& [id, stream] : summary.streams) {
      lost += stream.lost;
      duplicated += stream.duplicated;
    }
    std::printf(
        "%s: boards %d, messages sent %llu (dropped at the boards %llu, acknowledged by the broker "
        "%llu), received %llu, lost %llu, duplicated %llu, board reconnects %llu, %.2f s\n",
        name, boards, static_cast<unsigned long long>(run.queued),
        static_cast<unsigned long long>(run.dropped),
        static_cast<unsigned long long>(run.published),
        static_cast<unsigned long long>(summary.messages), static_cast<unsigned long long>(lost),
        static_cast<unsigned long long>(duplicated),
        static_cast<unsigned long long>(run.reconnects), run.seconds);
    RecordProperty("boards", boards);
    RecordProperty("sent", static_cast<int>(run.queued));
    RecordProperty("received", static_cast<int>(summary.messages));
    RecordProperty("lost", static_cast<int>(lost));
  }
};

TEST_F(Fleet, FiftyBoardsOneBrokerNothingLostAtQos1) {
  test::MosquittoBroker broker(folder_);
  auto listener = start_listener(broker);
  const FleetRun run = run_fleet(broker, [] {});
  const Summary summary = stop_listener(std::move(listener));
  report("fleet", run, summary);

  EXPECT_EQ(run.queued, boards * messages_per_board);
  EXPECT_EQ(run.dropped, 0U);
  EXPECT_EQ(run.published, run.queued);
  EXPECT_EQ(summary.messages, boards * messages_per_board);
  EXPECT_EQ(summary.corrupt, 0U);
  ASSERT_EQ(summary.streams.size(), static_cast<std::size_t>(boards));
  for (const auto& [id, stream] : summary.streams) {
    EXPECT_EQ(stream.received, messages_per_board) << "stream " << id;
    EXPECT_EQ(stream.lost, 0U) << "stream " << id;
  }
}

// A fleet of JSON and binary boards (`?format=json` on the listener's URI as a user writes it):
// every JSON payload is decoded and counted like a binary one, none is called corrupt.
TEST_F(Fleet, JsonAndBinaryBoardsAllDecodedAndCounted) {
  test::MosquittoBroker broker(folder_);
  auto listener = start_listener(broker, "fleet/#?format=json");
  const FleetRun run = run_fleet(
      broker, [] {}, [](int board) { return board % 2 == 0 ? "json" : "binary"; });
  const Summary summary = stop_listener(std::move(listener));
  report("fleet json and binary", run, summary);

  EXPECT_EQ(run.published, boards * messages_per_board);
  EXPECT_EQ(summary.messages, boards * messages_per_board);
  EXPECT_EQ(summary.corrupt, 0U);
  ASSERT_EQ(summary.streams.size(), static_cast<std::size_t>(boards));
  for (const auto& [id, stream] : summary.streams) {
    EXPECT_EQ(stream.received, messages_per_board) << "stream " << id;
    EXPECT_EQ(stream.lost, 0U) << "stream " << id;
    EXPECT_EQ(stream.duplicated, 0U) << "stream " << id;
  }
}

// A payload that starts like JSON but is not a track message is counted as corrupt, with the
// field that failed named, never silently ignored.
TEST_F(Fleet, MalformedJsonPayloadCountedAsCorruptWithItsReason) {
  test::MosquittoBroker broker(folder_);
  auto listener = start_listener(broker);
  // A plain libmosquitto client: our publisher only ever sends well-formed messages.
  mosquitto_lib_init();
  mosquitto* client = mosquitto_new("malformed-json-board", true, nullptr);
  ASSERT_NE(client, nullptr);
  ASSERT_EQ(mosquitto_connect(client, "127.0.0.1", broker.port(), 10), MOSQ_ERR_SUCCESS);
  const auto publish = [&](const std::string& payload) {
    ASSERT_EQ(mosquitto_publish(client, nullptr, "fleet/bad", static_cast<int>(payload.size()),
                                payload.data(), 1, false),
              MOSQ_ERR_SUCCESS);
    // QoS 1: a few loop turns send the message and take the broker's acknowledgement.
    for (int turn = 0; turn < 10; ++turn) mosquitto_loop(client, 50, 1);
  };
  publish(R"({"schema":2,"stream":7})");
  publish("{not json");
  mosquitto_disconnect(client);
  mosquitto_destroy(client);
  const Summary summary = stop_listener(std::move(listener));
  EXPECT_EQ(summary.messages, 0U);
  EXPECT_EQ(summary.corrupt, 2U);
  EXPECT_NE(test::read_text(folder_ / "listen.out").find("invalid JSON 2 (first: no \"sequence\")"),
            std::string::npos)
      << test::read_text(folder_ / "listen.out");
}

// One `rtmot run` as a child process: how it ended and its whole stderr, which every expectation on
// it prints (a bare "exit -1, expected 6" said nothing about why).
struct ChildRun {
  int status{-1};  // as waitpid gives it; -1: it did not end within the limit and was killed
  std::string err;
  int exit_code() const { return status != -1 && WIFEXITED(status) ? WEXITSTATUS(status) : -1; }
};

std::ostream& operator<<(std::ostream& out, const ChildRun& run) {
  if (run.status == -1) {
    out << "did not end within the limit and was killed";
  } else if (WIFSIGNALED(run.status)) {
    out << "ended by signal " << WTERMSIG(run.status);
  } else {
    out << "exit " << WEXITSTATUS(run.status);
  }
  return out << "; its stderr:\n" << run.err;
}

// `rtmot run` whose only output is MQTT: the final report says per output what was delivered; a
// broker never reached is named as such (not "connection lost") and the run exits 6 (it exited 0,
// silent about 0 messages delivered). Every frame is processed (--playback every-frame): at the
// default real-time pace a busy machine skips frames, and under load this test failed on "delivered
// 0 of 34 messages" where it expected 40.
TEST_F(Fleet, RunReportsDeliveriesAndFailsWhenNothingWasDelivered) {
  const auto sequence = test::shared_path("data/mot15-train/ADL-Rundle-6");
  RTMOT_REQUIRE_FILE(sequence / "det/det.txt");
  std::filesystem::create_directories(folder_);
  { std::ofstream(folder_ / "replay.yaml") << "detector:\n  kind: replay\n"; }
  // Each run's output files have their own names: a failed test's folder keeps both.
  const auto run = [&](const std::string& name, const std::string& mqtt_uri) {
    test::ChildProcess rtmot(
        {RTMOT_BINARY, "run", "--config", (folder_ / "replay.yaml").string(), "--source",
         "mot-seq://" + sequence.string(), "--det-file", (sequence / "det/det.txt").string(),
         "--playback", "every-frame", "--max-frames", "40", "--mqtt", mqtt_uri},
        folder_ / (name + ".out"), folder_ / (name + ".err"));
    ChildRun result;
    result.status = rtmot.wait(60s);
    result.err = test::read_text(folder_ / (name + ".err"));
    return result;
  };
  {
    test::MosquittoBroker broker(folder_);
    const ChildRun delivered = run("run-broker", broker.mqtt_uri("rtmot/board1"));
    EXPECT_EQ(delivered.exit_code(), 0) << delivered;
    EXPECT_NE(delivered.err.find("output mqtt: delivered 40 of 40 messages"), std::string::npos)
        << delivered;
  }
  const std::string nowhere = "mqtt://127.0.0.1:" + std::to_string(test::free_tcp_port()) + "/t";
  const ChildRun lost = run("run-nowhere", nowhere);
  EXPECT_EQ(lost.exit_code(), 6) << lost;
  EXPECT_NE(lost.err.find("cannot reach the broker"), std::string::npos) << lost;
  EXPECT_EQ(lost.err.find("connection lost"), std::string::npos) << lost;
  EXPECT_NE(lost.err.find("delivered 0 of 40 messages"), std::string::npos) << lost;
  EXPECT_NE(lost.err.find("was never reached"), std::string::npos) << lost;
  EXPECT_NE(lost.err.find("no output delivered any message"), std::string::npos) << lost;
}

TEST_F(Fleet, BrokerRestartedMidRunLossCountedPublishingResumes) {
  test::MosquittoBroker broker(folder_);
  auto listener = start_listener(broker);
  const FleetRun run = run_fleet(broker, [&] {
    std::this_thread::sleep_for(600ms);  // about 30 messages per board in
    broker.stop();
    std::this_thread::sleep_for(300ms);
    broker.start();
  });
  const Summary summary = stop_listener(std::move(listener));
  report("fleet with broker restart", run, summary);

  EXPECT_EQ(run.queued, boards * messages_per_board);  // the boards' queues held the outage
  EXPECT_EQ(run.dropped, 0U);
  EXPECT_EQ(run.published, run.queued);  // and the restarted broker took every message
  EXPECT_GE(run.reconnects, static_cast<std::uint64_t>(boards));
  ASSERT_EQ(summary.streams.size(), static_cast<std::size_t>(boards));
  std::uint64_t received = 0;
  for (const auto& [id, stream] : summary.streams) {
    // Every board was heard after the restart, and the listener's books balance: what it did not
    // receive of each board's sequence is counted as lost (losses after the last received message
    // cannot be seen; the last message is always delivered here, as publishing resumed).
    EXPECT_EQ(stream.received + stream.lost, messages_per_board) << "stream " << id;
    received += stream.received;
  }
  EXPECT_EQ(received, summary.messages);
}

}  // namespace
}  // namespace rtmot::outputs
