// `rtmot run`: the real-time pipeline (source -> SSD or replay detector -> SORT -> sinks) from a
// YAML configuration, with command-line overrides. Ends at the end of the stream, --max-frames or
// SIGINT/SIGTERM (all exit 0), after draining, flushing and the final report.
#include <spdlog/spdlog.h>

#include <memory>
#include <string>
#include <vector>

#include "apps/number_checks.hpp"
#include "apps/subcommand.hpp"
#include "apps/tracker_flags.hpp"
#include "common/exit_codes.hpp"
#include "common/input_error.hpp"
#include "detector/coco_labels.hpp"
#include "outputs/delivery_report.hpp"
#include "outputs/overlay.hpp"
#include "pipeline/pipeline.hpp"
#include "platform/board.hpp"
#include "platform/signals.hpp"
#include "runner/host_port.hpp"
#include "runner/run_config.hpp"
#include "runner/run_setup.hpp"
#include "tracker/presets.hpp"

namespace rtmot::app {
namespace {

struct RunOverrides {
  std::string config_file;
  std::string model;
  float threshold{-1.F};
  std::string classes;
  std::string preset;
  std::string overlay;
  int metrics_port{-1};
  std::vector<std::string> sources;  // --source, repeatable
  std::string playback;
  double latency_ms{0.0};
  std::string udp;
  std::string mqtt;
  std::string jsonl;
  std::string binary;
  std::string video_out;
  std::string report;
  std::string det_file;
  std::int64_t max_frames{-1};
  double stats_interval_s{-1.0};
  std::int64_t stream_id{-1};
  TrackerFlags tracker_flags;
};

// "person,car" or "1,3" (names from the COCO map, or ids); "all" = every class.
std::vector<int> parse_classes(const std::string& text) {
  std::vector<int> classes;
  if (text == "all") return classes;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string word = text.substr(start, comma - start);
    int id = detector::coco_class_id(word);
    if (id < 0 && !word.empty() && word.find_first_not_of("0123456789") == std::string::npos &&
        word.size() <= 2) {
      id = std::stoi(word);
      if (detector::coco_label(id).empty()) id = -1;
    }
    if (id < 0) {
      throw InputError("", 0, "--classes",
                       "'" + word + "' is not a COCO class name or id (e.g. person,car or 1,3)",
                       ExitCode::usage);
    }
    classes.push_back(id);
    start = comma + 1;
  }
  return classes;
}

void apply(const RunOverrides& overrides, runner::RunConfig& config) {
  if (!overrides.model.empty()) {
    config.detector.kind = "ssd";
    config.detector.model = overrides.model;
  }
  if (overrides.threshold >= 0.F) config.detector.score_threshold = overrides.threshold;
  if (!overrides.classes.empty()) config.detector.classes = parse_classes(overrides.classes);
  if (!overrides.preset.empty()) {
    // The preset replaces the file's tracker section, as `rtmot track --preset` does.
    const auto preset = tracker::find_preset(overrides.preset);
    if (!preset) {
      throw InputError("", 0, "--preset", "expected one of: " + tracker::preset_names(),
                       ExitCode::usage);
    }
    config.tracker = *preset;
    config.tracker.frame_rate = 0.0;  // from the source
    config.tracker.image_width = 0.F;
    config.tracker.image_height = 0.F;
    config.tracker.detection_threshold = 0.F;  // the detector's threshold is the one cut
  }
  if (!overrides.overlay.empty()) config.output.overlay = overrides.overlay;
  if (overrides.metrics_port >= 0) config.output.metrics_port = overrides.metrics_port;
  if (!overrides.sources.empty()) {
    // Replaces the file's source(s); each keeps the file's `source` capture settings.
    runner::SourceConfig settings = config.source;
    settings.stream_id = -1;
    config.sources.clear();
    for (const std::string& uri : overrides.sources) {
      settings.uri = uri;
      config.sources.push_back(settings);
    }
    config.source = config.sources.front();
    if (config.sources.size() == 1)
      config.sources.clear();
    else
      config.source.uri.clear();
  }
  if (!overrides.playback.empty()) {
    const auto mode = pipeline::parse_playback_mode(overrides.playback);
    if (!mode) {
      throw InputError("", 0, "--playback", "expected every-frame, realtime or simulated",
                       ExitCode::usage);
    }
    config.playback.mode = *mode;
  }
  if (overrides.latency_ms > 0.0) config.playback.latency_ms = overrides.latency_ms;
  if (!overrides.udp.empty()) {
    runner::parse_host_port(overrides.udp, "command line", 0, "--udp", ExitCode::usage);
    config.output.udp = overrides.udp;
  }
  if (!overrides.mqtt.empty()) config.output.mqtt = overrides.mqtt;
  if (!overrides.jsonl.empty()) config.output.jsonl_file = overrides.jsonl;
  if (!overrides.binary.empty()) config.output.binary_file = overrides.binary;
  if (!overrides.video_out.empty()) config.output.video_file = overrides.video_out;
  if (!overrides.report.empty()) config.output.report_file = overrides.report;
  if (!overrides.det_file.empty()) config.detector.det_file = overrides.det_file;
  if (overrides.max_frames >= 0) config.max_frames = overrides.max_frames;
  if (overrides.stats_interval_s >= 0.0) config.stats_interval_s = overrides.stats_interval_s;
  if (overrides.stream_id >= 0) config.stream_id = static_cast<std::uint32_t>(overrides.stream_id);
  overrides.tracker_flags.apply(config.tracker);
}

int run(const RunOverrides& overrides) {
  // Before any thread exists: every thread inherits the blocked SIGINT/SIGTERM.
  platform::StopSignals signals;
  runner::RunConfig config = overrides.config_file.empty()
                                 ? runner::default_run_config()
                                 : runner::load_run_config(overrides.config_file);
  apply(overrides, config);
  runner::validate(config);
  // Every output is checked before the source opens and the model loads: a bad target is one
  // clear error line at once.
  runner::prepare_video_output(config);

  spdlog::info("board: {}", platform::describe(platform::detect_board()));
  // Every source opens before any output: a bad URI in a list fails the run with nothing written.
  auto inputs = runner::make_inputs(config);
  for (const auto& input : inputs) {
    const platform::SourceInfo& info = input.source->info();
    spdlog::info("source: {} ({}x{} at {:.2f} fps{}), stream id {}", info.uri, info.width,
                 info.height, info.fps, info.live ? ", live" : "", input.stream_id);
  }
  runner::RunOutputs outputs = runner::make_outputs(config, inputs);
  for (const auto& destination : outputs.destinations) spdlog::info("output: {}", destination);
  if (outputs.destinations.empty()) {
    spdlog::warn("no output configured: tracks go nowhere (--udp, --mqtt, --jsonl, --video-out)");
  }
  auto detector = runner::make_detector(config);
  spdlog::info("detector: {}", detector->describe());
  pipeline::Pipeline pipeline(std::move(inputs), std::move(detector), std::move(outputs.consumers),
                              runner::make_options(config));
  const pipeline::PipelineReport report = pipeline.run(signals.stop_flag());

  // The final report is the run's result: shown whatever --log-level says (warn hid it).
  const auto level = spdlog::get_level();
  if (level > spdlog::level::info && level != spdlog::level::off) {
    spdlog::set_level(spdlog::level::info);
  }
  spdlog::info("{}", pipeline::summary_line(report));
  if (report.streams.size() > 1) {
    for (const auto& stream : report.streams) spdlog::info("{}", pipeline::summary_line(stream));
  }
  if (!config.output.report_file.empty()) {
    pipeline::write_report(report, config.output.report_file);
    spdlog::info("report written to {}", config.output.report_file);
  }
  const outputs::DeliveryReport delivered = outputs::report_deliveries(outputs.deliveries);
  for (const auto& line : delivered.lines) {
    if (delivered.empty.empty()) {
      spdlog::info("output {}", line);
    } else {
      spdlog::error("output {}", line);
    }
  }
  const bool files_written = !config.output.jsonl_file.empty() ||
                             !config.output.binary_file.empty() ||
                             !config.output.video_file.empty();
  spdlog::set_level(level);
  if (delivered.nothing_delivered && !files_written) {
    spdlog::error("no output delivered any message: the tracks of this run went nowhere (exit {})",
                  to_int(ExitCode::network));
    return to_int(ExitCode::network);
  }
  bool failed = false;
  for (const auto& stream : report.streams) {
    if (stream.source_error.empty()) continue;
    spdlog::error("{}: the source failed: {}", stream.source, stream.source_error);
    failed = true;
  }
  if (failed) return to_int(ExitCode::source_failed);
  return to_int(ExitCode::ok);
}

}  // namespace

Subcommand add_run_command(CLI::App& parent) {
  auto overrides = std::make_shared<RunOverrides>();
  CLI::App* cli = parent.add_subcommand(
      "run",
      "Track in real time: video source -> detector -> tracker -> UDP/files (see "
      "docs/config.md)");
  cli->add_option("--config", overrides->config_file,
                  "YAML run configuration (configs/*.yaml); without it, the defaults of "
                  "docs/config.md and the options below");
  cli->add_option("--model", overrides->model, "the SSD's ONNX model (sets detector.kind ssd)");
  cli->add_option("--threshold", overrides->threshold, "detector score threshold in [0, 1]")
      ->check(finite_in(0.0, 1.0));
  cli->add_option(
      "--classes", overrides->classes,
      "classes to keep: COCO names or ids, comma-separated (person,car or 1,3), or all");
  cli->add_option(
      "--preset", overrides->preset,
      "tracker preset, replacing the file's tracker section: " + tracker::preset_names());
  cli->add_option("--overlay", overrides->overlay,
                  "what the video shows: " + outputs::overlay_flag_names() +
                      " (comma-separated), "
                      "or none");
  cli->add_option("--metrics-port", overrides->metrics_port,
                  "serve Prometheus metrics on http://127.0.0.1:PORT/metrics (0 = off)")
      ->check(integer_in(0, 65535));
  cli->add_option("--source", overrides->sources,
                  "source URI: file path, v4l2:///dev/videoN, csi://N, rtsp://..., test://..., "
                  "mot-seq://SEQUENCE_DIR; repeat for several sources (one batched detector)")
      ->allow_extra_args(false);  // one URI per --source
  cli->add_option("--playback", overrides->playback, "every-frame, realtime or simulated")
      ->check(CLI::IsMember({"every-frame", "realtime", "simulated"}));
  cli->add_option("--latency-ms", overrides->latency_ms, "simulated detector latency (ms)")
      ->check(finite_in(1e-3, 3'600'000.0));
  cli->add_option("--udp", overrides->udp, "send track messages to HOST:PORT");
  cli->add_option(
      "--mqtt", overrides->mqtt,
      "publish track messages to mqtt://HOST[:PORT]/TOPIC[?qos=0|1&format=binary|json]");
  cli->add_option("--jsonl", overrides->jsonl, "write track messages as JSON lines to FILE");
  cli->add_option("--binary", overrides->binary, "write binary track messages to FILE");
  cli->add_option(
      "--video-out", overrides->video_out,
      "annotated video: FILE.mp4/.mkv, rtsp://:8554/NAME, rtp://HOST:PORT, display://0");
  cli->add_option("--report", overrides->report, "write the final report as JSON to FILE");
  cli->add_option("--det-file", overrides->det_file, "replay detector: MOTChallenge det.txt");
  cli->add_option("--max-frames", overrides->max_frames, "stop after N captured frames")
      ->check(integer_in(0, 1'000'000'000'000));
  cli->add_option("--stats-interval", overrides->stats_interval_s,
                  "seconds between progress lines (0 = none)")
      ->check(finite_in(0.0, 86'400.0));
  cli->add_option("--stream-id", overrides->stream_id, "stream id in every message")
      ->check(integer_in(0, 4294967295));
  overrides->tracker_flags.add_to(*cli);
  return {cli, [overrides] { return run(*overrides); }, /*stops_on_signals=*/true};
}

}  // namespace rtmot::app
