// `rtmot run`: the real-time pipeline (source -> SSD or replay detector -> SORT -> sinks) from a
// YAML configuration, with command-line overrides. Ends at the end of the stream, --max-frames or
// SIGINT/SIGTERM (all exit 0), after draining, flushing and the final report. SIGHUP re-reads the
// configuration file (runner/config_reloader.hpp).
#include <spdlog/spdlog.h>

#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "apps/subcommand.hpp"
#include "common/exit_codes.hpp"
#include "common/input_error.hpp"
#include "outputs/delivery_report.hpp"
#include "outputs/report_json.hpp"
#include "pipeline/pipeline.hpp"
#include "platform/board.hpp"
#include "platform/signals.hpp"
#include "runner/class_choice.hpp"
#include "runner/config_reloader.hpp"
#include "runner/run_config.hpp"
#include "runner/run_flags.hpp"
#include "runner/run_setup.hpp"

namespace rtmot::app {
namespace {

struct RunCommand {
  std::string config_file;
  runner::RunFlags flags;
};

// A run shorter than a scrape interval (a recorded file) ends before Prometheus sees its last
// counts: with metrics_linger_s the endpoint stays up, showing the final values, until the time is
// up or a signal asks to stop. Polled every 100 ms: StopSignals offers a flag, not a wait.
void linger_with_final_metrics(const runner::OutputConfig& output,
                               const runner::RunOutputs& outputs,
                               const platform::StopSignals& signals) {
  if (!outputs.metrics_server || !(output.metrics_linger_s > 0.0) || signals.stop_requested())
    return;
  spdlog::info("metrics: the final values served at {} for {} s more (SIGINT/SIGTERM ends it)",
               outputs.metrics_server->url(), output.metrics_linger_s);
  const auto until =
      std::chrono::steady_clock::now() + std::chrono::duration<double>(output.metrics_linger_s);
  while (!signals.stop_requested() && std::chrono::steady_clock::now() < until)
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
}

// Takes each SIGHUP on a thread of its own while the pipeline runs: a reload reads a file and
// takes the editors' locks, which no pipeline thread may wait for.
class ReloadThread {
 public:
  ReloadThread(const platform::StopSignals& signals, std::function<void()> reload)
      : thread_([this, &signals, reload = std::move(reload)] {
          std::uint64_t seen = 0;
          // Polls `done_` every 200 ms: the wait is for a SIGHUP, and the end of the run is rare.
          while (!done_.load(std::memory_order_acquire)) {
            const std::uint64_t now = signals.wait_for_reload(seen, std::chrono::milliseconds(200));
            if (now == seen) continue;
            seen = now;
            // A reload reports its own errors; anything else must not end the process either.
            try {
              reload();
            } catch (const std::exception& error) {
              spdlog::error("SIGHUP: the reload failed: {}; the running configuration is kept",
                            error.what());
            }
          }
        }) {}
  ~ReloadThread() {
    done_.store(true, std::memory_order_release);
    thread_.join();
  }
  ReloadThread(const ReloadThread&) = delete;
  ReloadThread& operator=(const ReloadThread&) = delete;

 private:
  std::atomic<bool> done_{false};
  std::thread thread_;
};

int run(const RunCommand& command) {
  // Before any thread exists: every thread inherits the blocked SIGINT/SIGTERM/SIGHUP.
  platform::StopSignals signals(platform::Hangup::reloads);
  runner::RunConfig config = command.config_file.empty()
                                 ? runner::default_run_config()
                                 : runner::load_run_config(command.config_file);
  command.flags.apply(config);
  runner::validate(config);
  // Every output is checked before the source opens and the model loads: a bad target is one
  // clear error line at once.
  runner::prepare_video_output(config);
  runner::check_model_found(config);
  runner::check_classes(config);  // names of the model's labels: known now

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
    spdlog::warn(
        "no output configured: tracks go nowhere (--udp, --mqtt, --jsonl, --video-out, "
        "--mot-results)");
  }
  auto detectors = runner::make_detectors(config, runner::source_infos(inputs));
  spdlog::info("detector: {}", detectors.front()->describe());
  runner::start_web_server(config, outputs, detectors.front()->describe());
  if (outputs.web_server) {
    spdlog::info("web: the operator's page at {} (its files from {})", outputs.web_server->url(),
                 outputs.web_server->static_dir().string());
  }
  pipeline::PipelineOptions options = runner::make_options(config);
  options.score_cut = outputs.score_cut.get();
  pipeline::Pipeline pipeline(std::move(inputs), std::move(detectors), std::move(outputs.consumers),
                              options);
  std::unique_ptr<runner::ConfigReloader> reloader;
  if (outputs.events_editor && !config.loaded_from.empty()) {
    reloader = std::make_unique<runner::ConfigReloader>(
        config.loaded_from, command.flags, *outputs.events_editor, *outputs.settings_editor,
        *outputs.score_cut, *outputs.document);
  }
  pipeline::PipelineReport report;
  {
    const ReloadThread reloading(signals, [&reloader] {
      if (reloader) {
        reloader->reload();
      } else {
        spdlog::warn("SIGHUP: nothing to re-read (the run has no --config); nothing changed");
      }
    });
    report = pipeline.run(signals.stop_flag());
  }
  if (outputs.metrics) outputs.metrics->sources_ended();

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
    outputs::write_report(report, config.output.report_file);
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
  linger_with_final_metrics(config.output, outputs, signals);
  const bool files_written = !config.output.jsonl_file.empty() ||
                             !config.output.binary_file.empty() ||
                             config.output.video.has_value() || !config.output.mot_results.empty();
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
  auto command = std::make_shared<RunCommand>();
  CLI::App* cli = parent.add_subcommand(
      "run",
      "Track in real time: video source -> detector -> tracker -> UDP/files (see "
      "docs/config.md)");
  cli->add_option("--config", command->config_file,
                  "YAML run configuration (configs/*.yaml); without it, the defaults of "
                  "docs/config.md and the options below");
  // Every other flag comes from the settings' tables (runner/run_settings.hpp).
  command->flags.add_to(*cli);
  return {cli, [command] { return run(*command); }, /*stops_on_signals=*/true};
}

}  // namespace rtmot::app
