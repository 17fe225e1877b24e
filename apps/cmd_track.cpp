// `rtmot track`: runs the tracker over MOTChallenge sequences' detections and writes one results
// file per sequence; reports the tracker's own speed (time inside Tracker::update only).
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <string>

#include "apps/number_checks.hpp"
#include "apps/subcommand.hpp"
#include "common/exit_codes.hpp"
#include "common/frame_rate.hpp"
#include "common/input_error.hpp"
#include "motio/mot_files.hpp"
#include "motio/processed_frames.hpp"
#include "motio/results_writer.hpp"
#include "motio/sequence_folders.hpp"
#include "motio/track_runner.hpp"
#include "platform/log_setup.hpp"
#include "platform/signals.hpp"
#include "runner/run_config.hpp"
#include "runner/tracker_flags.hpp"
#include "tracker/presets.hpp"
#include "tracker/score_scale.hpp"
#include "tracker/tracker_config.hpp"

namespace rtmot::app {
namespace {

namespace fs = std::filesystem;

constexpr double kProgressEverySeconds = 3.0;

struct TrackCommandOptions {
  std::string dataset;
  std::string out_dir;
  std::string preset{tracker::default_preset_name()};
  runner::TrackerFlags tracker_flags;
  int interval{1};
  std::string detections{"det/det.txt"};
};

// The preset first, then every option given on the command line.
tracker::TrackerConfig make_config(const TrackCommandOptions& options) {
  tracker::TrackerConfig config;
  if (!runner::apply_preset(options.preset, config)) {
    throw InputError(
        "command line", 0, "--preset",
        "unknown preset '" + options.preset + "' (known: " + tracker::preset_names() + ")",
        ExitCode::usage);
  }
  options.tracker_flags.apply(config);
  return config;
}

// A detections file whose scores do not fit the configuration's absolute cuts gets one warning
// naming the file and the range seen (tracker/score_scale.hpp); the run goes on.
void warn_on_score_scale(const fs::path& file, const tracker::TrackerConfig& config) {
  if (file.filename() == "gt.txt") return;  // the perfect detector: every score is 1
  tracker::ScoreRange range;
  for (const auto& row : motio::read_mot_file(file, motio::MotFileKind::detections))
    range.include(row.conf);
  if (const auto warning = tracker::score_scale_warning(config, range))
    spdlog::warn("{}: {}", file.string(), *warning);
}

int run_track(const TrackCommandOptions& options) {
  platform::StopSignals signals;  // a stop ends the sequence in progress, unwritten
  motio::TrackOptions track_options;
  track_options.config = make_config(options);
  track_options.detections = options.detections;
  track_options.interval = options.interval;
  track_options.stop = &signals.stop_flag();
  const auto sequences = motio::find_sequences(options.dataset);
  std::vector<NamedFile> outputs;
  for (const auto& sequence : sequences) {
    outputs.push_back({motio::sequence_file(options.out_dir, sequence.info.name, ".txt"), "--out"});
    outputs.push_back({motio::processed_frames_file(options.out_dir, sequence.info.name), "--out"});
  }
  platform::check_files_and_open_log(motio::sequence_inputs(sequences, {options.detections}),
                                     outputs);
  std::error_code error;
  fs::create_directories(options.out_dir, error);
  if (error) throw InputError(options.out_dir, 0, "--out", "cannot create: " + error.message());

  int total_frames = 0;
  std::int64_t total_update_ns = 0;
  int written = 0;
  for (const auto& sequence : sequences) {
    warn_on_score_scale(sequence.dir / options.detections, track_options.config);
    using Clock = std::chrono::steady_clock;
    auto next_report = Clock::now() + std::chrono::duration<double>(kProgressEverySeconds);
    const auto progress = [&](int frame, int length) {
      if (Clock::now() < next_report) return;
      next_report = Clock::now() + std::chrono::duration<double>(kProgressEverySeconds);
      spdlog::info("{}: frame {} of {}", sequence.info.name, frame, length);
    };
    const motio::TrackRun run = motio::track_detections(
        motio::load_detections(sequence.dir / track_options.detections, sequence.info),
        sequence.info, track_options, progress);
    if (run.stopped) break;
    if (run.frames_over_capacity > 0) {
      spdlog::warn(
          "{}: {} frames had more detections than max_detections ({}, up to {}): the tracker used "
          "the first {} of each (raise --max-detections)",
          run.info.name, run.frames_over_capacity, track_options.config.max_detections,
          run.most_detections, track_options.config.max_detections);
    }
    const fs::path out_file = motio::sequence_file(options.out_dir, run.info.name, ".txt");
    motio::ResultsWriter results(out_file);
    for (const auto& row : run.tracks) results.write(row);
    // With the frames processed, for `rtmot eval --processed-frames`: both or neither.
    motio::publish_results_and_frames(results,
                                      motio::processed_frames_file(options.out_dir, run.info.name),
                                      run.processed_frames);
    ++written;
    fmt::print("{:<16} {:>6} frames {:>7} boxes  tracker {:>9.0f} Hz  -> {}\n", run.info.name,
               run.frames_processed, run.tracks.size(),
               frames_per_second(run.frames_processed, run.update_ns), out_file.string());
    std::fflush(stdout);
    total_frames += run.frames_processed;
    total_update_ns += run.update_ns;
  }
  if (signals.stop_requested()) {
    spdlog::warn("stopped: {} of {} sequences written (each whole), the rest not started", written,
                 sequences.size());
    return to_int(ExitCode::ok);
  }
  fmt::print("{:<16} {:>6} frames  tracker {:.0f} Hz (time inside Tracker::update only)\n",
             "OVERALL", total_frames, frames_per_second(total_frames, total_update_ns));
  return to_int(ExitCode::ok);
}

}  // namespace

Subcommand add_track_command(CLI::App& parent) {
  auto options = std::make_shared<TrackCommandOptions>();
  CLI::App* cli = parent.add_subcommand(
      "track",
      "Run the tracker on MOTChallenge sequences' detections; writes OUT/<sequence>.txt in the "
      "MOTChallenge results format and OUT/<sequence>.frames, the frames processed (for `rtmot "
      "eval --processed-frames`)");
  cli->add_option("--dataset", options->dataset,
                  "a sequence folder (with seqinfo.ini) or a folder of them")
      ->required();
  cli->add_option("--out", options->out_dir, "folder for the results files")->required();
  cli->add_option(
         "--preset", options->preset,
         "starting configuration (" + tracker::preset_names() + "); options below override it")
      ->capture_default_str();
  options->tracker_flags.add_to(*cli, motio::kSequenceSuppliedOptions,
                                "rtmot track takes it from each sequence's seqinfo.ini");
  cli->add_option("--interval", options->interval,
                  "process frames 1, 1+N, 1+2N, ... only (frame numbers and times kept)")
      ->check(integer_in(1, motio::kMaxFrame))
      ->capture_default_str();
  cli->add_option("--det", options->detections,
                  "detections file relative to each sequence folder (gt/gt.txt = perfect detector)")
      ->capture_default_str();
  return {cli, [options] { return run_track(*options); }, /*stops_on_signals=*/true};
}

}  // namespace rtmot::app
