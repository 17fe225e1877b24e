// `rtmot study`: the frame-rate study. Tracks every configuration of study/study_plan.hpp on both
// inputs at every interval, the presets on the synthetic detectors, and the cross-validation of the
// default's candidates (study/study_cv.hpp); scores each run with the `rtmot eval` scorer on the
// processed frames, and writes tables and plots (docs/study/ is made by scripts/study.sh).
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "apps/number_checks.hpp"
#include "apps/subcommand.hpp"
#include "common/exit_codes.hpp"
#include "common/input_error.hpp"
#include "common/output_file.hpp"
#include "motio/mot_files.hpp"
#include "motio/sequence_folders.hpp"
#include "platform/cpu_share.hpp"
#include "platform/log_setup.hpp"
#include "platform/signals.hpp"
#include "study/detector_cut.hpp"
#include "study/latency_sweep.hpp"
#include "study/run_progress.hpp"
#include "study/study_cv.hpp"
#include "study/study_dataset.hpp"
#include "study/study_plan.hpp"
#include "study/study_report.hpp"
#include "study/study_runner.hpp"
#include "tracker/presets.hpp"

namespace rtmot::app {
namespace {

struct StudyCommandOptions {
  std::string dataset;
  std::string out_dir;
  int jobs{2};
  std::vector<int> intervals{study::default_study_intervals()};
  bool quick{false};
  bool no_synthetic{false};
  bool no_cv{false};
  std::string only;
  std::string link_prefix;
  bool latency{false};
  bool detector_cut{false};
};

// A study's tables, plots and folds are only meaningful complete: a stop (SIGINT, SIGTERM) ends
// the runs in progress and writes nothing, as a clean stop (exit 0).
int stopped(const char* phase) {
  spdlog::warn("study: stopped during {}: nothing written (its tables need every run)", phase);
  return to_int(ExitCode::ok);
}

// Prints study::run_progress_line at most every `interval` (and at the last run), from whichever
// worker thread finished a run.
class RunProgressPrinter {
 public:
  RunProgressPrinter(std::string what, std::chrono::steady_clock::duration interval)
      : what_(std::move(what)),
        interval_(interval),
        start_(std::chrono::steady_clock::now()),
        last_line_(start_) {}

  void update(std::size_t done, std::size_t total) {
    const auto now = std::chrono::steady_clock::now();
    // A few hundred runs of about a second each: a lock per run costs nothing here.
    const std::lock_guard<std::mutex> lock(mutex_);
    if (now - last_line_ < interval_ && done < total) return;
    last_line_ = now;
    spdlog::info(
        "{}: {}", what_,
        study::run_progress_line(done, total, std::chrono::duration<double>(now - start_).count()));
  }

 private:
  std::string what_;
  std::chrono::steady_clock::duration interval_;
  std::chrono::steady_clock::time_point start_;
  std::mutex mutex_;
  std::chrono::steady_clock::time_point last_line_;
};

// --latency: the default and SORT behind simulated detector latencies (study/latency_sweep.hpp).
int run_latency_sweep(const StudyCommandOptions& options, const platform::StopSignals& signals) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const auto dataset = study::load_study_dataset(options.dataset);
  const std::vector<std::string> presets = {std::string(tracker::default_preset_name()), "sort"};
  const std::vector<study::StudyInput> inputs = {study::StudyInput::detections,
                                                 study::StudyInput::ground_truth};
  const auto latencies = study::default_latencies();
  spdlog::info(
      "study: latency sweep: {} sequences, {} presets x {} inputs x {} latencies on {} "
      "threads",
      dataset.size(), presets.size(), inputs.size(), latencies.size(), options.jobs);
  const auto tables = study::run_latency_sweep(dataset, presets, inputs, latencies, options.jobs,
                                               &signals.stop_flag());
  if (signals.stop_requested()) return stopped("the latency sweep");
  const auto files = study::write_latency_sweep(options.out_dir, tables);
  spdlog::info("study: wrote {} files under {}/latency in {:.0f} s", files.size(), options.out_dir,
               std::chrono::duration<double>(Clock::now() - start).count());
  return to_int(ExitCode::ok);
}

// --detector-cut: the presets on the SSD's score model with its low detections dropped at each
// cut before the tracker (study/detector_cut.hpp): where the pipeline's SSD should cut.
int run_detector_cut(const StudyCommandOptions& options) {
  const auto dataset = study::load_study_dataset(options.dataset);
  const std::vector<std::string> presets = {std::string(tracker::default_preset_name()),
                                            "bytetrack", "sort"};
  std::vector<int> intervals = options.intervals;
  std::sort(intervals.begin(), intervals.end());
  intervals.erase(std::unique(intervals.begin(), intervals.end()), intervals.end());
  const auto tables = study::run_detector_cut_sweep(dataset, presets, "synth-ssd",
                                                    study::default_detector_cuts(), intervals);
  const auto path = std::filesystem::path(options.out_dir) / "detector-cut.md";
  std::error_code error;
  std::filesystem::create_directories(options.out_dir, error);  // write_whole_file names it
  write_whole_file(path, study::format_detector_cut_markdown(tables, intervals));
  spdlog::info("study: wrote {}", path.string());
  return to_int(ExitCode::ok);
}

int run_study_command(const StudyCommandOptions& options) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const platform::CpuSample cpu_start = platform::sample_cpu();
  const platform::StopSignals signals;
  // The tables are written under --out, which holds no input; the log file may not name one.
  platform::check_files_and_open_log(
      motio::sequence_inputs(motio::find_sequences(options.dataset), {"det/det.txt", "gt/gt.txt"}),
      {});
  if (options.latency) return run_latency_sweep(options, signals);
  if (options.detector_cut) return run_detector_cut(options);
  // Ascending and unique: rows and plot axes follow the interval.
  std::vector<int> intervals = options.intervals;
  std::sort(intervals.begin(), intervals.end());
  intervals.erase(std::unique(intervals.begin(), intervals.end()), intervals.end());
  const auto dataset = study::load_study_dataset(options.dataset);
  auto configurations = study::study_configurations(options.quick);
  if (!options.only.empty()) {
    configurations.erase(std::remove_if(configurations.begin(), configurations.end(),
                                        [&](const auto& c) {
                                          return c.name.find(options.only) == std::string::npos;
                                        }),
                         configurations.end());
    if (configurations.empty()) {
      throw InputError("", 0, "--only", "no configuration name contains '" + options.only + "'",
                       ExitCode::usage);
    }
  }
  const std::vector<study::StudyInput> inputs = {study::StudyInput::detections,
                                                 study::StudyInput::ground_truth};
  spdlog::info("study: {} sequences, {} configurations x {} inputs x {} intervals on {} threads",
               dataset.size(), configurations.size(), inputs.size(), intervals.size(),
               options.jobs);
  const auto progress = [](int done, int total, const study::StudyTable& table, int interval) {
    // A held-back detector's scores go to its tables only: a log read while a default is still
    // being chosen must not show how any candidate does on it (docs/study.md, the protocol).
    if (study::is_held_back(table.input)) {
      spdlog::info("[{}/{}] {} on {} interval {}: held back (in the tables only)", done, total,
                   table.configuration.name, study::to_string(table.input), interval);
      return;
    }
    for (const auto& row : table.rows) {
      if (row.interval == interval) {
        spdlog::info("[{}/{}] {} on {} interval {}: MOTA {:.1f} IDF1 {:.1f}", done, total,
                     table.configuration.name, study::to_string(table.input), interval,
                     row.metrics.mota, row.metrics.idf1);
        return;
      }
    }
  };
  auto tables = study::run_study(dataset, configurations, inputs, intervals, options.jobs, progress,
                                 &signals.stop_flag());
  if (signals.stop_requested()) return stopped("the runs");
  if (!options.no_synthetic) {
    // The presets on detectors they were never tuned on (study/synthetic_detector.hpp).
    std::vector<study::StudyConfiguration> presets;
    for (const auto& configuration : configurations) {
      if (configuration.group == "presets") presets.push_back(configuration);
    }
    // Those the cross-validation chooses on, and those held back from every choice.
    std::vector<study::StudyInput> detectors = study::synthetic_inputs();
    for (const auto& input : study::held_back_inputs()) detectors.push_back(input);
    spdlog::info("study: {} presets x {} synthetic detectors ({} held back)", presets.size(),
                 detectors.size(), study::held_back_inputs().size());
    for (auto& table : study::run_study(dataset, presets, detectors, intervals, options.jobs,
                                        progress, &signals.stop_flag()))
      tables.push_back(std::move(table));
    if (signals.stop_requested()) return stopped("the synthetic detectors");
  }
  std::string folds;
  if (!options.no_cv && dataset.size() >= 2) {
    const auto candidates = study::cv_candidates(options.quick);
    spdlog::info(
        "study: cross-validation (one sequence and one detector left out) of {} candidates",
        candidates.size());
    // The public detections and every synthetic detector: each is left out in turn.
    std::vector<study::StudyInput> detectors = {study::StudyInput::detections};
    for (const auto& input : study::synthetic_inputs()) detectors.push_back(input);
    // What the default must hold against on every detector and interval: SORT and ByteTrack.
    std::vector<study::StudyConfiguration> references;
    for (const char* name : {"sort", "bytetrack"})
      references.push_back({std::string("preset-") + name, "cv", *tracker::find_preset(name)});
    RunProgressPrinter printer("study: cross-validation", std::chrono::seconds(10));
    const auto cv = study::cross_validate(
        dataset, candidates, detectors, intervals, options.jobs, &signals.stop_flag(), references,
        [&printer](std::size_t done, std::size_t total) { printer.update(done, total); });
    if (signals.stop_requested()) return stopped("the cross-validation");
    for (const auto& table : cv.tables) tables.push_back(table);
    folds = study::format_folds_markdown(cv);
    spdlog::info("study: cross-validation chose {} on all sequences", cv.in_sample_choice);
  }
  auto files = study::write_study(options.out_dir, tables, options.link_prefix);
  if (!folds.empty()) {
    const auto path = std::filesystem::path(options.out_dir) / "cv-folds.md";
    write_whole_file(path, folds);
    files.push_back(path);
  }
  spdlog::info("study: wrote {} files under {} in {:.0f} s", files.size(), options.out_dir,
               std::chrono::duration<double>(Clock::now() - start).count());
  // --jobs N is N threads that never wait for each other; whether they had N cores is the
  // machine's doing (issue 22: "2 threads used about one core"), and this line says which.
  spdlog::info("study: {}",
               platform::describe_cpu_share(platform::cpu_share(cpu_start, platform::sample_cpu()),
                                            options.jobs));
  return to_int(ExitCode::ok);
}

}  // namespace

Subcommand add_study_command(CLI::App& parent) {
  auto options = std::make_shared<StudyCommandOptions>();
  CLI::App* cli = parent.add_subcommand(
      "study",
      "Frame-rate study: every predictor x affinity, tracker option and preset at several frame "
      "intervals, on det/det.txt and on gt/gt.txt as a perfect detector; the presets on "
      "synthetic detectors made from the ground truth (those held back from every choice "
      "included); cross-validation of the default's candidates; tables and SVG plots");
  cli->add_option("--dataset", options->dataset,
                  "a sequence folder (with seqinfo.ini) or a folder of them")
      ->required();
  cli->add_option("--out", options->out_dir, "folder for tables/, plots/ and summary.md")
      ->required();
  cli->add_option("--jobs", options->jobs, "worker threads")
      ->check(integer_in(1, 256))
      ->capture_default_str();
  cli->add_option("--intervals", options->intervals, "frame intervals, e.g. 1,2,3,5,10,15,30")
      ->delimiter(',')
      ->check(integer_in(1, motio::kMaxFrame));
  cli->add_flag(
      "--quick", options->quick,
      "kalman-iou, the options, the ablation and the presets only (no predictor x affinity grid)");
  cli->add_option("--only", options->only, "only configurations whose name contains this");
  cli->add_flag("--no-synthetic", options->no_synthetic,
                "skip the presets on the synthetic detectors made from the ground truth");
  cli->add_flag("--no-cv", options->no_cv,
                "skip the leave-one-sequence-out cross-validation (with --quick: 2 candidates)");
  cli->add_flag("--latency", options->latency,
                "only the latency sweep: the default and the sort preset behind a simulated "
                "detector of 33..1000 ms (fixed and jittered), skipping frames as the pipeline "
                "does; scored on the processed frames and at the full frame rate (OUT/latency/)");
  cli->add_flag(
      "--detector-cut", options->detector_cut,
      "only the detector's own cut: the default, bytetrack and sort presets on the "
      "synthetic SSD (synth-ssd) with its detections below 0.5 .. 0.15 dropped before the "
      "tracker, at --intervals (OUT/detector-cut.md)");
  cli->add_option("--link-prefix", options->link_prefix,
                  "prefix of the plot links in summary.md (e.g. study/ when it is included from "
                  "docs/study.md)");
  return {cli, [options] { return run_study_command(*options); }};
}

}  // namespace rtmot::app
