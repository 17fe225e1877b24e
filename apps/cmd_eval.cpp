// `rtmot eval`: scores MOTChallenge result files against ground truth with the devkit's rules and
// prints its table (plus HOTA), per sequence and OVERALL.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <memory>
#include <string>

#include "apps/number_checks.hpp"
#include "apps/subcommand.hpp"
#include "common/exit_codes.hpp"
#include "common/output_file.hpp"
#include "mot/evaluation.hpp"
#include "mot/metrics_report.hpp"
#include "motio/mot_files.hpp"
#include "motio/sequence_folders.hpp"
#include "platform/log_setup.hpp"
#include "platform/signals.hpp"

namespace rtmot::app {
namespace {

struct EvalOptions {
  std::string gt_dir;
  std::string results_dir;
  int interval{1};
  bool processed_frames{false};
  std::string csv_path;
  std::string json_path;
};

// Results of a run that processed every Nth frame, scored at every frame, count each frame it
// never saw as misses (MOT15, rtmot preset at interval 5: MOTA 7.1 instead of 36.0): say so.
void warn_if_sampled(const mot::EvaluationReport& report) {
  int every = 0;
  int sampled = 0;
  for (const auto& sequence : report.sequences) {
    if (sequence.results_every < 2) continue;
    ++sampled;
    every = every == 0 || every == sequence.results_every ? sequence.results_every : -1;
  }
  if (sampled == 0) return;
  const std::string interval = every > 0 ? std::to_string(every) : "N";
  spdlog::warn(
      "results of {} of {} sequences hold only frames 1, 1+{}, 1+2x{}, ...: scored at every frame, "
      "the frames in between count as misses. If the run processed only those frames, score them "
      "with --interval {} or --processed-frames (the <sequence>.frames lists `rtmot track` writes)",
      sampled, report.sequences.size(), interval, interval, interval);
}

int run_eval(const EvalOptions& options) {
  platform::StopSignals signals;  // a stop ends scoring before the next sequence
  platform::check_files_and_open_log(motio::sequence_inputs(motio::find_sequences(options.gt_dir),
                                                            {"gt/gt.txt"}, {options.results_dir}),
                                     {{options.csv_path, "--csv"}, {options.json_path, "--json"}});
  const mot::EvaluationReport report =
      mot::evaluate(options.gt_dir, options.results_dir,
                    mot::EvaluationScope{options.interval, options.processed_frames},
                    &signals.stop_flag(), [](const mot::SequenceScore& score) {
                      spdlog::info("{}: scored ({} frames)", score.name, score.counts.clear.frames);
                    });
  if (report.stopped) {
    // A table of some sequences would read as the dataset's score: nothing is printed or written.
    spdlog::warn("stopped after scoring {} of {} sequences: no table printed or written",
                 report.sequences.size(), report.sequences_in_dataset);
    return to_int(ExitCode::ok);
  }
  if (options.interval == 1 && !options.processed_frames) warn_if_sampled(report);
  fmt::print("{}", mot::format_table(report));
  std::fflush(stdout);
  if (!options.csv_path.empty()) {
    write_whole_file(options.csv_path, mot::format_csv(report));
    spdlog::info("wrote {}", options.csv_path);
  }
  if (!options.json_path.empty()) {
    write_whole_file(options.json_path, mot::format_json(report));
    spdlog::info("wrote {}", options.json_path);
  }
  return to_int(ExitCode::ok);
}

}  // namespace

Subcommand add_eval_command(CLI::App& parent) {
  auto options = std::make_shared<EvalOptions>();
  CLI::App* cli = parent.add_subcommand(
      "eval",
      "Score MOTChallenge results against ground truth exactly as the official devkit (CLEAR MOT, "
      "identity metrics) plus HOTA; prints one line per sequence and OVERALL");
  cli->add_option("--gt", options->gt_dir,
                  "a sequence folder (seqinfo.ini + gt/gt.txt) or a folder of them")
      ->required();
  cli->add_option("--results", options->results_dir, "folder holding <sequence>.txt per sequence")
      ->required();
  CLI::Option* interval =
      cli->add_option("--interval", options->interval,
                      "score only frames 1, 1+N, 1+2N, ... (as `rtmot track --interval N`)")
          ->check(integer_in(1, motio::kMaxFrame))
          ->capture_default_str();
  cli->add_flag("--processed-frames", options->processed_frames,
                "score only the frames listed in RESULTS/<sequence>.frames (one frame number per "
                "line, as `rtmot track` writes them beside its results): the frames a run "
                "processed")
      ->excludes(interval);
  cli->add_option("--csv", options->csv_path, "also write the table as CSV to this file");
  cli->add_option("--json", options->json_path, "also write full-precision results as JSON");
  return {cli, [options] { return run_eval(*options); }, /*stops_on_signals=*/true};
}

}  // namespace rtmot::app
