// `rtmot listen`: receives track messages (UDP, or a binary file sink's output with --read), prints
// them, and ends with what arrived, was lost, came late or twice, or was corrupt, per stream.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "apps/number_checks.hpp"
#include "apps/subcommand.hpp"
#include "common/input_error.hpp"
#include "detector/label_table.hpp"
#include "messages/json_line_decoder.hpp"
#include "messages/jsonl_sink.hpp"
#include "messages/message_file_reader.hpp"
#include "messages/message_format.hpp"
#include "messages/message_stream_stats.hpp"
#include "outputs/listen_board.hpp"
#include "outputs/listen_web_server.hpp"
#include "outputs/mqtt_subscriber.hpp"
#include "outputs/mqtt_uri.hpp"
#include "platform/clock.hpp"
#include "platform/host_port.hpp"
#include "platform/log_setup.hpp"
#include "platform/signals.hpp"
#include "platform/udp_socket.hpp"

namespace rtmot::app {
namespace {

using messages::Arrival;
using messages::DecodedMessage;
using messages::DecodeError;
using messages::ListenerStats;

// A count a listener can reach (one datagram a nanosecond for 11 days): anything larger means
// "no limit", which is spelled 0.
constexpr std::int64_t kMaxCount = 1'000'000'000'000'000;

struct ListenOptions {
  std::uint16_t port{0};
  std::string bind_address{"0.0.0.0"};
  std::uint64_t count{0};  // datagrams (or file records); 0 = no limit
  double duration_s{0.0};  // 0 = no limit
  double stats_every_s{5.0};
  std::string jsonl_path;
  std::string labels_path;  // the boards' model's labels file; empty: COCO's table
  std::string read_path;
  std::string mqtt_uri;
  int web_port{0};  // the ground station's page (docs/web.md); 0 = off
  std::string web_bind{"127.0.0.1"};
  bool quiet{false};
};

constexpr int poll_interval_ms =
    200;  // how often a quiet socket checks for Ctrl-C, duration, stats

const char* describe(messages::Arrival arrival) {
  switch (arrival) {
    case messages::Arrival::first:
      return " (first)";
    case messages::Arrival::in_order:
      return "";
    case messages::Arrival::after_gap:
      return " (after a gap)";
    case messages::Arrival::late:
      return " (late)";
    case messages::Arrival::duplicate:
      return " (duplicate)";
    case messages::Arrival::restart:
      return " (sender restarted)";
    case messages::Arrival::clash:
      return " (CLASH: another sender uses this stream id)";
  }
  return "";
}

double to_ms(double ns) {
  return ns / 1e6;
}

void print_message(const messages::DecodedMessage& message, messages::Arrival arrival) {
  const auto& frame = message.frame;
  fmt::print(
      "stream {} seq {} frame {}: {} tracks{}{}, latency {:.1f} ms, skipped {}{}{}\n",
      frame.stream_id, frame.sequence, frame.frame_number, frame.tracks.size(),
      message.truncated() ? fmt::format(" of {} (truncated)", message.total_track_count) : "",
      frame.predicted ? (frame.observed ? " predicted, observed" : " predicted") : "",
      to_ms(static_cast<double>(message.latency_ns())), frame.frames_dropped, describe(arrival),
      frame.end_of_stream ? " (end of stream)" : "");
  for (const auto& event : frame.events) {  // docs/events.md
    fmt::print("  event {} {} track {}{}{}\n", events::kEventKindNames.name(event.kind),
               event.index, event.track_id,
               event.dwell_seconds > 0.0 ? fmt::format(" after {:.1f} s", event.dwell_seconds) : "",
               event.lost ? " (lost inside)" : "");
  }
}

void print_corrupt(messages::DecodeError reason, std::size_t size) {
  fmt::print("corrupt message ({} bytes): {}\n", size, messages::to_string(reason));
}

void print_corrupt_json(const std::string& problem, std::size_t size) {
  fmt::print("corrupt JSON message ({} bytes): {}\n", size, problem);
}

/// Payloads that looked like JSON (first byte '{') but did not read as a track message.
struct InvalidJson {
  std::uint64_t count{0};
  std::string first_problem;
};

void print_stats_line(const messages::ListenerStats& stats, const InvalidJson& invalid_json,
                      double elapsed_s) {
  std::uint64_t lost = 0;
  for (const auto& entry : stats.streams()) lost += entry.second.sequences.lost();
  fmt::print("[{:.1f} s] received {}, lost {}, corrupt {}, streams {}\n", elapsed_s,
             stats.received(), lost, stats.corrupt() + invalid_json.count, stats.streams().size());
  std::fflush(stdout);
}

/// `elapsed_s` < 0: not a timed run (a file).
void print_summary(const messages::ListenerStats& stats, const InvalidJson& invalid_json,
                   double elapsed_s) {
  fmt::print("summary{}: {} messages, {} corrupt, {} streams\n",
             elapsed_s >= 0 ? fmt::format(" after {:.1f} s", elapsed_s) : std::string(),
             stats.received(), stats.corrupt() + invalid_json.count, stats.streams().size());
  if (stats.evicted_streams() > 0) {
    fmt::print(
        "  {} more streams ({} messages) not listed: evicted, least recently heard first, to keep "
        "at most {} streams\n",
        stats.evicted_streams(), stats.evicted_messages(), stats.streams().size());
  }
  for (const auto& [id, stream] : stats.streams()) {
    const auto& seq = stream.sequences;
    fmt::print(
        "  stream {}: received {}, lost {}, reordered {}, duplicated {}, restarts {}, "
        "truncated {}; latency min/mean/max {:.2f}/{:.2f}/{:.2f} ms; sender skipped {} frames\n",
        id, seq.received(), seq.lost(), seq.reordered(), seq.duplicated(), seq.restarts(),
        stream.truncated, to_ms(static_cast<double>(stream.latency_min_ns)),
        to_ms(stream.latency_mean_ns()), to_ms(static_cast<double>(stream.latency_max_ns)),
        stream.last_frames_dropped);
    if (stream.predicted > 0) {
      fmt::print(
          "  stream {}: predicted {} of them (full-rate output: frames the sender's detector "
          "skipped, sent with the tracks' predicted boxes)\n",
          id, stream.predicted);
    }
    for (const auto& [kind_and_index, count] : stream.events.listed()) {
      fmt::print("  stream {}: events {} {}: {}\n", id,
                 events::kEventKindNames.name(static_cast<events::EventKind>(kind_and_index.first)),
                 kind_and_index.second, count);
    }
    if (stream.events.unlisted() > 0) {
      fmt::print(
          "  stream {}: {} more events of other kinds and indexes, not listed: at most {} "
          "(kind, index) pairs are counted apart per stream\n",
          id, stream.events.unlisted(), messages::EventTally::max_pairs);
    }
    if (seq.clashes() > 0) {
      fmt::print(
          "  stream {}: CLASH: {} messages no single sender could have sent (sequence and "
          "timestamp disagree): two senders use stream id {}; they are not counted above\n",
          id, seq.clashes(), id);
    }
  }
  if (stats.corrupt() + invalid_json.count > 0) {
    fmt::print("  corrupt by reason:");
    for (std::size_t i = 1; i < messages::decode_error_count; ++i) {
      const auto reason = static_cast<messages::DecodeError>(i);
      if (stats.corrupt(reason) > 0)
        fmt::print(" {} {};", messages::to_string(reason), stats.corrupt(reason));
    }
    if (invalid_json.count > 0)
      fmt::print(" invalid JSON {} (first: {});", invalid_json.count, invalid_json.first_problem);
    fmt::print("\n");
  }
  std::fflush(stdout);
}

// The binary messages carry class ids only: the names are the boards' model's, given here.
messages::ClassLabelFn class_labels(const ListenOptions& options) {
  const auto labels = std::make_shared<const detector::LabelTable>(
      options.labels_path.empty() ? detector::LabelTable::coco()
                                  : detector::LabelTable::from_file(options.labels_path));
  return [labels](int class_id) { return labels->name(class_id); };
}

/// The ground station's page (--web-port): what it shows, and its server. Off: both null.
struct ListenPage {
  std::unique_ptr<outputs::ListenBoard> board;
  std::unique_ptr<outputs::ListenWebServer> server;  // after board: stopped before it goes
};

ListenPage start_page(const ListenOptions& options) {
  ListenPage page;
  if (options.web_port <= 0) return page;
  page.board =
      std::make_unique<outputs::ListenBoard>(class_labels(options), platform::steady_now_ns());
  page.server = std::make_unique<outputs::ListenWebServer>(
      *page.board, options.web_bind, static_cast<std::uint16_t>(options.web_port),
      outputs::ListenWebServer::find_static_dir());
  spdlog::info("web: the ground station's page at {} (its files from {})", page.server->url(),
               page.server->static_dir().string());
  return page;
}

/// What both modes do with one message's bytes. `board`: the page's (null: no page).
class MessageHandler {
 public:
  MessageHandler(const ListenOptions& options, outputs::ListenBoard* board)
      : quiet_(options.quiet), board_(board) {
    if (!options.jsonl_path.empty()) {
      jsonl_ = std::make_unique<messages::JsonlSink>(options.jsonl_path, class_labels(options));
    }
  }

  /// A binary message or a JSON line (an MQTT board with format=json), told apart by the first
  /// byte: a fleet subscription may hold both kinds of board.
  void handle(const std::uint8_t* data, std::size_t size) {
    if (messages::looks_like_json(data, size)) {
      handle_json(data, size);
      return;
    }
    const messages::DecodeError error = messages::decode_message(data, size, decoded_);
    if (error != messages::DecodeError::none) {
      handle_corrupt(error, size);
      return;
    }
    record(decoded_);
  }

  void handle_corrupt(messages::DecodeError reason, std::size_t size) {
    stats_.record_corrupt(reason);
    if (board_ != nullptr) board_->set_corrupt(stats_.corrupt() + invalid_json_.count);
    if (!quiet_) print_corrupt(reason, size);
  }

  void flush() {
    if (jsonl_) jsonl_->flush();
  }
  const messages::ListenerStats& stats() const { return stats_; }
  const InvalidJson& invalid_json() const { return invalid_json_; }

 private:
  void handle_json(const std::uint8_t* data, std::size_t size) {
    std::string problem;
    if (!messages::decode_json_line(data, size, decoded_, problem)) {
      if (invalid_json_.count++ == 0) invalid_json_.first_problem = problem;
      if (board_ != nullptr) board_->set_corrupt(stats_.corrupt() + invalid_json_.count);
      if (!quiet_) print_corrupt_json(problem, size);
      return;
    }
    record(decoded_);
  }

  void record(const messages::DecodedMessage& message) {
    const messages::Arrival arrival = stats_.record(message);
    if (board_ != nullptr) {
      // Timed on reception by our own clock: the board's clock may be wrong.
      board_->record(message, arrival, stats_.streams().at(message.frame.stream_id),
                     platform::steady_now_ns());
    }
    if (!quiet_) print_message(message, arrival);
    if (jsonl_) jsonl_->write(message);
  }

  bool quiet_;
  outputs::ListenBoard* board_;
  InvalidJson invalid_json_;
  messages::DecodedMessage
      decoded_;  // reused: decoding allocates nothing once it has seen the largest frame
  messages::ListenerStats stats_;
  std::unique_ptr<messages::JsonlSink> jsonl_;
};

int listen_udp(const ListenOptions& options) {
  platform::StopSignals signals;  // before anything else: see its header
  platform::UdpReceiver receiver(options.bind_address, options.port);
  const ListenPage page = start_page(options);
  MessageHandler handler(options, page.board.get());
  spdlog::info("listening on udp://{}", receiver.local_address());

  // Room for the largest UDP payload: a longer message than we send is still seen, and rejected.
  std::vector<std::uint8_t> datagram(messages::message::max_message_size + 1);
  const std::int64_t start_ns = platform::steady_now_ns();
  const auto elapsed_s = [start_ns] {
    return static_cast<double>(platform::steady_now_ns() - start_ns) / 1e9;
  };
  double next_stats_s = options.stats_every_s;
  std::uint64_t datagrams = 0;
  while (!signals.stop_requested()) {
    if (options.count > 0 && datagrams >= options.count) break;
    if (options.duration_s > 0 && elapsed_s() >= options.duration_s) break;
    if (options.stats_every_s > 0 && elapsed_s() >= next_stats_s) {
      print_stats_line(handler.stats(), handler.invalid_json(), elapsed_s());
      next_stats_s += options.stats_every_s;
    }
    std::size_t size = 0;
    bool cut = false;
    const auto status =
        receiver.receive(datagram.data(), datagram.size(), poll_interval_ms, size, cut);
    if (status != platform::ReceiveStatus::datagram) continue;
    ++datagrams;
    if (cut) {
      handler.handle_corrupt(messages::DecodeError::length_mismatch,
                             size);  // longer than any message
    } else {
      handler.handle(datagram.data(), size);
    }
  }
  handler.flush();
  print_summary(handler.stats(), handler.invalid_json(), elapsed_s());
  return to_int(ExitCode::ok);
}

int listen_mqtt(const ListenOptions& options) {
  platform::StopSignals signals;  // before libmosquitto's thread exists: see its header
  std::string problem;
  const auto uri =
      outputs::parse_mqtt_uri(options.mqtt_uri, problem, outputs::MqttTopicUse::subscribe);
  if (!uri) throw InputError(options.mqtt_uri, 0, "--mqtt", problem, ExitCode::usage);
  const ListenPage page = start_page(options);
  MessageHandler handler(options, page.board.get());
  // The handler runs on libmosquitto's thread; the main thread reads the counts for the stats
  // line, the limits and the summary. A listener is not a hot path: a mutex is the simple choice.
  std::mutex handler_mutex;
  std::uint64_t messages_seen = 0;
  outputs::MqttSubscriber subscriber(*uri, [&](const std::uint8_t* payload, std::size_t size) {
    const std::lock_guard<std::mutex> lock(handler_mutex);
    ++messages_seen;
    handler.handle(payload, size);
  });
  spdlog::info("listening on {}", outputs::to_string(*uri));

  const std::int64_t start_ns = platform::steady_now_ns();
  const auto elapsed_s = [start_ns] {
    return static_cast<double>(platform::steady_now_ns() - start_ns) / 1e9;
  };
  double next_stats_s = options.stats_every_s;
  while (!signals.stop_requested()) {
    if (const std::string failure = subscriber.failure(); !failure.empty()) {
      throw InputError(outputs::to_string(*uri), 0, "--mqtt", failure, ExitCode::network);
    }
    {
      const std::lock_guard<std::mutex> lock(handler_mutex);
      if (options.count > 0 && messages_seen >= options.count) break;
      if (options.stats_every_s > 0 && elapsed_s() >= next_stats_s) {
        print_stats_line(handler.stats(), handler.invalid_json(), elapsed_s());
        next_stats_s += options.stats_every_s;
      }
    }
    if (options.duration_s > 0 && elapsed_s() >= options.duration_s) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(poll_interval_ms));
  }
  const std::lock_guard<std::mutex> lock(handler_mutex);
  handler.flush();
  print_summary(handler.stats(), handler.invalid_json(), elapsed_s());
  return to_int(ExitCode::ok);
}

int read_file(const ListenOptions& options) {
  messages::MessageFileReader reader(options.read_path);
  MessageHandler handler(options, nullptr);
  std::vector<std::uint8_t> record;
  messages::FileReadStatus status = messages::FileReadStatus::message;
  while (options.count == 0 || reader.records_read() < options.count) {
    status = reader.next(record);
    if (status != messages::FileReadStatus::message) break;
    handler.handle(record.data(), record.size());
  }
  handler.flush();
  print_summary(handler.stats(), handler.invalid_json(), -1.0);
  if (status == messages::FileReadStatus::broken_framing) {
    // Everything before the break was read and reported; the file itself is malformed.
    throw InputError(options.read_path, 0, "", reader.problem());
  }
  return to_int(ExitCode::ok);
}

}  // namespace

Subcommand add_listen_command(CLI::App& parent) {
  auto options = std::make_shared<ListenOptions>();
  CLI::App* cli = parent.add_subcommand(
      "listen",
      "Receive track messages over UDP or MQTT (or read a binary message file), print them and "
      "count lost, reordered, duplicated and corrupt messages per stream; --web-port shows every "
      "stream in a browser");
  auto* port = cli->add_option("--port,-p", options->port,
                               "UDP port to listen on (0: any free port, logged at start)")
                   ->check(integer_in(0, 65535));
  auto* bind =
      cli->add_option("--bind", options->bind_address, "local address to bind (IPv4 or IPv6)")
          ->check(bind_address())
          ->capture_default_str();
  cli->add_option("--count,-n", options->count,
                  "stop after this many datagrams/records (0 = no limit)")
      ->check(integer_in(0, kMaxCount));
  auto* duration = cli->add_option("--duration", options->duration_s,
                                   "stop after this many seconds (0 = no limit)")
                       ->check(finite_in(0.0, 1e9));
  cli->add_option("--stats-every", options->stats_every_s,
                  "print running counts every S seconds (0 = never)")
      ->check(finite_in(0.0, 1e9))
      ->capture_default_str();
  auto* jsonl = cli->add_option("--jsonl", options->jsonl_path,
                                "also write every valid message to this JSON-lines file");
  auto* labels = cli->add_option(
      "--labels", options->labels_path,
      "the boards' model's labels file (one name per line, the first the background): names the "
      "classes in --jsonl's \"label\" and on the page (default: COCO's table)");
  auto* read =
      cli->add_option("--read", options->read_path, "decode a binary message file instead of UDP");
  cli->add_flag("--quiet,-q", options->quiet,
                "print no line per message, only stats and the summary");
  auto* mqtt = cli->add_option(
      "--mqtt", options->mqtt_uri,
      "subscribe to an MQTT broker instead of UDP: mqtt://HOST[:PORT]/TOPIC (wildcards + and # "
      "allowed; binary and JSON payloads (`run --mqtt ...?format=json`) are both read, told apart "
      "by their first byte)");
  auto* web_port =
      cli->add_option("--web-port", options->web_port,
                      "serve the ground station's page (every stream's tracks drawn live, its "
                      "counts and losses; docs/web.md) on this TCP port; 0 = off")
          ->check(integer_in(0, 65535));
  cli->add_option("--web-bind", options->web_bind,
                  "the address the page listens on (0.0.0.0: every network; docs/web.md's threat "
                  "model first)")
      ->check(bind_address())
      ->capture_default_str()
      ->needs(web_port);
  read->excludes(port)->excludes(bind)->excludes(duration)->excludes(web_port);
  mqtt->excludes(port)->excludes(bind)->excludes(read);
  cli->callback([port, read, mqtt, labels, jsonl, web_port] {
    if (port->count() == 0 && read->count() == 0 && mqtt->count() == 0)
      throw CLI::RequiredError("--port (or --read FILE, or --mqtt URI)");
    if (labels->count() > 0 && jsonl->count() == 0 && web_port->count() == 0)
      throw CLI::ValidationError("--labels", "names classes for --jsonl or --web-port: give one");
  });
  return {cli, [options] {
            platform::check_files_and_open_log({{options->read_path, "--read"}},
                                               {{options->jsonl_path, "--jsonl"}});
            if (!options->mqtt_uri.empty()) return listen_mqtt(*options);
            return options->read_path.empty() ? listen_udp(*options) : read_file(*options);
          }};
}

}  // namespace rtmot::app
