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
#include "platform/signals.hpp"

namespace rtmot::app {
namespace {

struct EvalOptions {
  std::string gt_dir;
  std::string results_dir;
  int interval{1};
  std::string csv_path;
  std::string json_path;
};

int run_eval(const EvalOptions& options) {
  platform::StopSignals signals;  // a stop ends scoring before the next sequence
  check_distinct_files(motio::sequence_inputs(motio::find_sequences(options.gt_dir), {"gt/gt.txt"},
                                              {options.results_dir}),
                       {{options.csv_path, "--csv"}, {options.json_path, "--json"}});
  const mot::EvaluationReport report =
      mot::evaluate(options.gt_dir, options.results_dir, options.interval, &signals.stop_flag(),
                    [](const mot::SequenceScore& score) {
                      spdlog::info("{}: scored ({} frames)", score.name, score.counts.clear.frames);
                    });
  if (report.stopped) {
    // A table of some sequences would read as the dataset's score: nothing is printed or written.
    spdlog::warn("stopped after scoring {} of {} sequences: no table printed or written",
                 report.sequences.size(), report.sequences_in_dataset);
    return to_int(ExitCode::ok);
  }
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
  cli->add_option("--interval", options->interval,
                  "score only frames 1, 1+N, 1+2N, ... (as `rtmot track --interval N`)")
      ->check(integer_in(1, motio::kMaxFrame))
      ->capture_default_str();
  cli->add_option("--csv", options->csv_path, "also write the table as CSV to this file");
  cli->add_option("--json", options->json_path, "also write full-precision results as JSON");
  return {cli, [options] { return run_eval(*options); }, /*stops_on_signals=*/true};
}

}  // namespace rtmot::app
