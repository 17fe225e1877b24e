// The fleet benchmark: N simulated boards (200 by default), each an MqttPublisher with its own
// stream id and topic replaying MOT15 track messages (ETH-Bahnhof's published detections as
// tracks) at a camera's rate, through a real mosquitto on loopback to one `rtmot listen --mqtt`
// process. Prints messages/s through the broker, per-board loss (from the listener's summary) and
// the listener's CPU time per 1000 messages/s. Not a Google Benchmark loop: one run of S seconds
// is the measurement. Usage: fleet_bench [--boards N] [--fps F] [--seconds S] [--qos 0|1]
#include <sys/resource.h>
#include <sys/wait.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "child_process.hpp"
#include "message_test_data.hpp"
#include "mosquitto_broker.hpp"
#include "outputs/mqtt_publisher.hpp"

namespace {

using namespace std::chrono_literals;
using rtmot::outputs::MqttPublisher;

struct Options {
  int boards{200};
  double fps{10.0};
  double seconds{20.0};
  int qos{1};
};

Options parse(int argc, char** argv) {
  Options options;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i];
    const double value = std::atof(argv[i + 1]);
    if (key == "--boards")
      options.boards = static_cast<int>(value);
    else if (key == "--fps")
      options.fps = value;
    else if (key == "--seconds")
      options.seconds = value;
    else if (key == "--qos")
      options.qos = static_cast<int>(value);
    else {
      std::fprintf(stderr, "unknown option %s\n", key.c_str());
      std::exit(2);
    }
  }
  return options;
}

double cpu_seconds(const rusage& usage) {
  return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec) / 1e6;
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = parse(argc, argv);
  const auto per_board = static_cast<std::size_t>(options.fps * options.seconds);
  const auto frames = rtmot::test::frames_from_detections("ETH-Bahnhof", per_board);
  if (frames.size() < per_board) {
    std::fprintf(stderr, "ETH-Bahnhof has %zu frames, fewer than %zu\n", frames.size(), per_board);
    return 1;
  }
  const std::filesystem::path folder =
      std::filesystem::temp_directory_path() / ("rtmot-fleet-bench-" + std::to_string(::getpid()));
  std::filesystem::create_directories(folder);
  rtmot::test::MosquittoBroker broker(folder);

  rusage before{};
  getrusage(RUSAGE_CHILDREN, &before);  // nothing reaped yet: the broker still runs
  auto listener = std::make_unique<rtmot::test::ChildProcess>(
      std::vector<std::string>{RTMOT_BINARY, "listen", "--mqtt", broker.mqtt_uri("fleet/#"),
                               "--quiet", "--stats-every", "0"},
      folder / "listen.out", folder / "listen.err");
  const auto ready = std::chrono::steady_clock::now() + 20s;
  while (rtmot::test::read_text(folder / "listen.err").find("subscribed to") == std::string::npos) {
    if (std::chrono::steady_clock::now() > ready) {
      std::fprintf(stderr, "the listener did not subscribe\n");
      return 1;
    }
    std::this_thread::sleep_for(20ms);
  }

  std::vector<std::unique_ptr<MqttPublisher>> publishers;
  for (int board = 0; board < options.boards; ++board) {
    rtmot::outputs::MqttPublisherOptions publisher_options;
    std::string problem;
    publisher_options.uri =
        *rtmot::outputs::parse_mqtt_uri(broker.mqtt_uri("fleet/board" + std::to_string(board) +
                                                        "?qos=" + std::to_string(options.qos)),
                                        problem);
    publisher_options.client_id = "bench-board-" + std::to_string(board);
    publishers.push_back(std::make_unique<MqttPublisher>(publisher_options, 1000 + board));
  }
  const auto interval = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(1.0 / options.fps));
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::thread> threads;
  for (int board = 0; board < options.boards; ++board) {
    threads.emplace_back([&, board] {
      // Boards start spread over one frame interval, as real cameras are not in phase.
      auto next = start + interval * board / options.boards;
      for (std::size_t i = 0; i < per_board; ++i) {
        std::this_thread::sleep_until(next);
        auto frame = frames[i];
        frame.stream_id = 1000 + static_cast<std::uint32_t>(board);
        publishers[static_cast<std::size_t>(board)]->write(frame);
        next += interval;
      }
    });
  }
  for (auto& thread : threads) thread.join();
  std::uint64_t queued = 0;
  std::uint64_t dropped = 0;
  std::uint64_t published = 0;
  for (auto& publisher : publishers) {
    publisher->flush();
    queued += publisher->counters().queued.load();
    dropped += publisher->counters().dropped.load();
    published += publisher->counters().published.load();
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::this_thread::sleep_for(1s);  // the last messages reach the listener
  listener->stop(SIGTERM, 30s);
  listener.reset();
  rusage after{};
  getrusage(RUSAGE_CHILDREN, &after);
  const double listener_cpu = cpu_seconds(after) - cpu_seconds(before);

  const std::string summary = rtmot::test::read_text(folder / "listen.out");
  std::smatch match;
  std::uint64_t received = 0;
  std::uint64_t corrupt = 0;
  if (std::regex_search(
          summary, match,
          std::regex(R"(summary after [0-9.]+ s: (\d+) messages, (\d+) corrupt, (\d+) streams)"))) {
    received = std::stoull(match[1]);
    corrupt = std::stoull(match[2]);
  }
  std::uint64_t streams = 0;
  std::uint64_t lost_total = 0;
  std::uint64_t lost_max = 0;
  std::uint64_t received_min = UINT64_MAX;
  const std::regex stream(R"(stream \d+: received (\d+), lost (\d+))");
  for (auto it = std::sregex_iterator(summary.begin(), summary.end(), stream);
       it != std::sregex_iterator(); ++it) {
    ++streams;
    const std::uint64_t lost = std::stoull((*it)[2]);
    lost_total += lost;
    lost_max = std::max(lost_max, lost);
    received_min = std::min<std::uint64_t>(received_min, std::stoull((*it)[1]));
  }
  const double rate = static_cast<double>(received) / seconds;
  std::printf(
      "fleet_bench: %d boards x %.0f fps for %.1f s, QoS %d, one mosquitto on loopback, one "
      "`rtmot listen --mqtt`\n"
      "  sent %llu (dropped at the boards %llu, acknowledged by the broker %llu)\n"
      "  received %llu, corrupt %llu, streams heard %llu of %d\n"
      "  per-board loss: total %llu, worst board %llu; fewest received by one board %llu of %zu\n"
      "  throughput: %.0f messages/s through the broker\n"
      "  listener CPU: %.2f s over %.1f s = %.1f%% of a core, %.1f%% of a core per 1000 "
      "messages/s\n",
      options.boards, options.fps, seconds, options.qos, static_cast<unsigned long long>(queued),
      static_cast<unsigned long long>(dropped), static_cast<unsigned long long>(published),
      static_cast<unsigned long long>(received), static_cast<unsigned long long>(corrupt),
      static_cast<unsigned long long>(streams), options.boards,
      static_cast<unsigned long long>(lost_total), static_cast<unsigned long long>(lost_max),
      static_cast<unsigned long long>(streams > 0 ? received_min : 0), per_board, rate,
      listener_cpu, seconds, 100.0 * listener_cpu / seconds,
      rate > 0 ? 100.0 * listener_cpu / seconds / (rate / 1000.0) : 0.0);
  std::filesystem::remove_all(folder);
  return received == queued && lost_total == 0 ? 0 : 1;
}
