// `rtmot soak`: runs the pipeline of a run configuration again and again for a given time and
// reports, after every pass, resident memory (VmRSS), end-to-end latency percentiles and dropped
// frames, so that a leak or a slow drift shows as a trend. Memory must be flat after warm-up:
// the first third of the passes (model, codec and allocator caches; glibc's per-thread arenas grow
// for a few passes, as every pass starts new threads). Each pass builds everything anew, so object
// lifetimes (sources, detector, threads, sinks) are soaked too, not only the per-frame path.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "apps/number_checks.hpp"
#include "apps/subcommand.hpp"
#include "common/exit_codes.hpp"
#include "common/input_error.hpp"
#include "common/input_file.hpp"
#include "pipeline/pipeline.hpp"
#include "platform/signals.hpp"
#include "runner/class_choice.hpp"
#include "runner/run_config.hpp"
#include "runner/run_setup.hpp"

namespace rtmot::app {
namespace {

// A soak runs for at most a year, and no process grows by a petabyte: ranges that keep the
// arithmetic on them finite.
constexpr double kMaxSoakSeconds = 366.0 * 86'400.0;
constexpr double kMaxGrowthMb = 1e9;

struct SoakOptions {
  std::string config_path;
  double duration_s{60.0};
  double max_growth_mb{0.0};  // 0 = report only
};

/// Resident memory of this process in MiB, from /proc/self/status (0 if unavailable).
double resident_mb() {
  std::string text;
  try {
    text = read_text_file("/proc/self/status", 64 * 1024);  // the one input reader, bounded
  } catch (const InputError&) {
    return 0.0;
  }
  std::istringstream status(text);
  for (std::string line; std::getline(status, line);) {
    if (line.rfind("VmRSS:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;  // kB
  }
  return 0.0;
}

double ms(std::int64_t ns) {
  return static_cast<double>(ns) * 1e-6;
}

pipeline::PipelineReport run_once(const runner::RunConfig& config, const std::atomic<bool>& stop) {
  auto inputs = runner::make_inputs(config);
  auto detectors = runner::make_detectors(config, runner::source_infos(inputs));
  pipeline::Pipeline pipe(std::move(inputs), std::move(detectors),
                          pipeline::as_consumers(runner::make_sinks(config)),
                          runner::make_options(config));
  return pipe.run(stop);
}

// A pass runs the message outputs only (runner::make_sinks): the MOT results, report, video and
// metrics endpoint are what one `rtmot run` produces, not something to rewrite every pass. They
// were dropped without a word; now a configuration that asks for one is refused, naming it.
void refuse_outputs_of_a_run(const runner::RunConfig& config) {
  const runner::OutputConfig& output = config.output;
  const auto refuse = [&](const char* field) {
    throw InputError(config.file, 0, field,
                     "soak writes message outputs only (udp, binary_file, jsonl_file, mqtt); "
                     "remove it, or use rtmot run for it");
  };
  if (!output.mot_results.empty()) refuse("output.mot_results");
  if (!output.report_file.empty()) refuse("output.report_file");
  if (output.video) refuse("output.video_file");
  if (output.metrics_port > 0) refuse("output.metrics_port");
  if (output.web_port > 0) refuse("output.web_port");
}

int run_soak(const SoakOptions& options) {
  platform::StopSignals signals;  // first: threads started later inherit the blocked mask
  const runner::RunConfig config = runner::load_run_config(options.config_path);
  runner::validate(config);
  refuse_outputs_of_a_run(config);
  runner::check_model_found(config);
  runner::check_classes(config);  // names of the model's labels: known now

  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const auto elapsed_s = [&] {
    return std::chrono::duration<double>(Clock::now() - start).count();
  };
  const double rss_start = resident_mb();
  std::vector<double> rss_after_pass;
  fmt::print("soak start rss_mb={:.1f} config={} duration_s={:.0f}\n", rss_start,
             options.config_path, options.duration_s);
  int pass = 0;
  while (elapsed_s() < options.duration_s && !signals.stop_requested()) {
    const auto report = run_once(config, signals.stop_flag());
    ++pass;
    const double rss = resident_mb();
    rss_after_pass.push_back(rss);
    const auto& e2e = report.latency.of(pipeline::Stage::end_to_end);
    fmt::print(
        "soak pass={} t_s={:.0f} rss_mb={:.1f} captured={} processed={} dropped={} lost={} "
        "e2e_ms p50={:.1f} p95={:.1f} p99={:.1f} max={:.1f}{}\n",
        pass, elapsed_s(), rss, report.frames_captured, report.frames_processed,
        report.frames_dropped, report.frames_lost, ms(e2e.quantile_ns(0.50)),
        ms(e2e.quantile_ns(0.95)), ms(e2e.quantile_ns(0.99)), ms(e2e.max_ns()),
        report.source_error.empty() ? "" : " source_error=" + report.source_error);
    std::fflush(stdout);
  }
  if (rss_after_pass.empty()) rss_after_pass.push_back(resident_mb());
  const std::size_t warm_up_passes = std::max<std::size_t>(1, rss_after_pass.size() / 3);
  const double rss_warm = rss_after_pass[warm_up_passes - 1];
  const double rss = rss_after_pass.back();
  const double growth = rss - rss_warm;
  fmt::print(
      "soak end passes={} t_s={:.0f} rss_mb start={:.1f} after_warmup={:.1f} end={:.1f} "
      "growth_after_warmup={:+.1f}\n",
      pass, elapsed_s(), rss_start, rss_warm, rss, growth);
  if (options.max_growth_mb > 0.0 && pass > 2 && growth > options.max_growth_mb) {
    spdlog::error("soak: resident memory grew {:.1f} MiB after warm-up (limit {:.1f})", growth,
                  options.max_growth_mb);
    return to_int(ExitCode::internal_error);  // a leak is a bug
  }
  return to_int(ExitCode::ok);
}

}  // namespace

Subcommand add_soak_command(CLI::App& parent) {
  auto options = std::make_shared<SoakOptions>();
  CLI::App* cli = parent.add_subcommand(
      "soak",
      "Run a configuration's pipeline in a loop for a given time; report memory (VmRSS), "
      "latency percentiles and dropped frames after every pass");
  cli->add_option("--config,-c", options->config_path, "run configuration (YAML)")->required();
  cli->add_option("--duration", options->duration_s, "seconds to keep starting passes")
      ->check(positive_up_to(kMaxSoakSeconds))
      ->capture_default_str();
  cli->add_option("--max-growth-mb", options->max_growth_mb,
                  "fail (exit 1) if VmRSS grew more than this after warm-up (first third of the "
                  "passes); 0 = report only")
      ->check(finite_in(0.0, kMaxGrowthMb))
      ->capture_default_str();
  return {cli, [options] { return run_soak(*options); }, /*stops_on_signals=*/true};
}

}  // namespace rtmot::app
