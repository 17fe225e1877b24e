// `rtmot count`: counts line crossings and zone visits (events/) on MOTChallenge sequences, from a
// tracker's results files or from the ground truth, and with --reference compares each count with
// the ground truth counted at every frame: how far a tracker's counts are from the truth.
#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "apps/number_checks.hpp"
#include "apps/subcommand.hpp"
#include "common/exit_codes.hpp"
#include "common/input_error.hpp"
#include "common/input_file.hpp"
#include "common/yaml_section.hpp"
#include "events/events_yaml.hpp"
#include "events/offline_count.hpp"
#include "motio/mot_files.hpp"
#include "motio/sequence_folders.hpp"
#include "platform/log_setup.hpp"
#include "runner/yaml_document.hpp"

namespace rtmot::app {
namespace {

namespace fs = std::filesystem;

struct CountCommandOptions {
  std::string dataset;
  std::string lines_file;
  std::string tracks_dir;  // empty: the ground truth
  int interval{1};
  bool reference{false};
};

// As strictly as a run configuration: one document (runner/yaml_document.hpp), through the one
// input reader (a FIFO or /dev/zero named here would hang or fill memory).
YAML::Node load_lines_file(const std::string& file) {
  constexpr std::uint64_t kMaxLinesFileBytes = 1 << 20;
  return runner::load_one_document(read_text_file(file, kMaxLinesFileBytes), file, "a lines file");
}

// An id twice in one frame of the tracks counted: two boxes of one track at one time, which no
// tracker writes; `rtmot eval` refuses it too (mot/prepared_sequence.cpp).
void require_one_box_per_id_and_frame(const std::vector<events::FrameTrack>& tracks,
                                      const std::string& file) {
  std::set<std::pair<std::int64_t, int>> seen;
  for (const auto& track : tracks) {
    if (!seen.emplace(track.frame, track.report.id).second) {
      throw InputError(file, 0, "id",
                       "id " + std::to_string(track.report.id) + " appears twice in frame " +
                           std::to_string(track.frame));
    }
  }
}

// The ground truth as tracks: what the benchmark scores (conf 1, pedestrians where classes exist).
std::vector<events::FrameTrack> ground_truth(const motio::SequenceFolder& sequence) {
  std::vector<events::FrameTrack> tracks;
  for (const auto& row :
       motio::read_mot_file(sequence.dir / "gt" / "gt.txt", motio::MotFileKind::ground_truth,
                            sequence.info.length)) {
    if (row.conf == 0.F || (row.class_id >= 0 && row.class_id != 1)) continue;
    tracks.push_back({row.frame, {row.id, row.box, 1.F, 1, 0, 0}});
  }
  return tracks;
}

std::vector<events::FrameTrack> results(const fs::path& file, const motio::SequenceInfo& info) {
  std::vector<events::FrameTrack> tracks;
  for (const auto& row : motio::read_mot_file(file, motio::MotFileKind::results, info.length))
    tracks.push_back({row.frame, {row.id, row.box, row.conf, 1, 0, 0}});
  return tracks;
}

std::string percent(long part, long whole) {
  return whole > 0 ? fmt::format("{:.1f} %", 100.0 * static_cast<double>(part) / whole) : "n/a";
}

int run_count(const CountCommandOptions& options) {
  const YAML::Node document = load_lines_file(options.lines_file);
  if (!document.IsMap())
    throw InputError(options.lines_file, 1, "", "expected a mapping with the key sequences");
  // A key given twice (a sequence twice: one was silently ignored) or unknown is refused, as in a
  // run configuration (common/yaml_section.hpp).
  Section root(document, options.lines_file, "");
  const YAML::Node lines = root.child("sequences");
  root.reject_unknown();
  if (!lines.IsMap())
    throw InputError(options.lines_file, 1, "sequences", "expected a mapping of sequence names");
  const Section by_sequence(lines, options.lines_file, "sequences");
  const auto sequences = motio::find_sequences(options.dataset);
  std::vector<NamedFile> inputs = motio::sequence_inputs(
      sequences, {"gt/gt.txt"},
      options.tracks_dir.empty() ? std::vector<fs::path>{}
                                 : std::vector<fs::path>{options.tracks_dir});
  inputs.push_back({options.lines_file, "--lines"});
  platform::check_files_and_open_log(inputs, {});  // writes nothing but stdout and the log

  fmt::print("{:<16} {:<10} {:>6} {:>6}{}\n", "sequence", "line", "in", "out",
             options.reference ? fmt::format(" {:>6} {:>6}", "ref_in", "ref_out") : "");
  long total_error = 0;
  long total_reference = 0;
  for (const auto& sequence : sequences) {
    const std::optional<YAML::Node> found = by_sequence.find(sequence.info.name);
    const YAML::Node section = found.value_or(YAML::Node(YAML::NodeType::Undefined));
    if (!found) {
      throw InputError(options.lines_file, 0, "sequences." + sequence.info.name,
                       "no lines for this sequence of the dataset");
    }
    const events::EventsConfig config = events::resolve_events(
        events::read_events_spec(section, options.lines_file, "sequences." + sequence.info.name),
        sequence.info.width, sequence.info.height);
    const bool counting_truth = options.tracks_dir.empty();
    const fs::path tracks_file =
        counting_truth ? sequence.dir / "gt" / "gt.txt"
                       : motio::sequence_file(options.tracks_dir, sequence.info.name, ".txt");
    const auto tracks =
        counting_truth ? ground_truth(sequence) : results(tracks_file, sequence.info);
    require_one_box_per_id_and_frame(tracks, tracks_file.string());
    // The ground truth's boxes do not jitter like a detector's: it is counted with the fixed
    // minimum band, so that neither the reference nor the floor (the truth kept at frames 1,
    // 1 + N, ...: a perfect tracker that skips frames) moves with a measure taken on itself.
    events::EventsConfig fixed_band = config;
    fixed_band.dead_band.noise_factor = 0.0;
    const events::SequenceCounts counts =
        events::count_sequence(tracks, sequence.info.length, sequence.info.frame_rate,
                               options.interval, counting_truth ? fixed_band : config);
    events::SequenceCounts truth;
    if (options.reference) {
      truth = events::count_sequence(ground_truth(sequence), sequence.info.length,
                                     sequence.info.frame_rate, 1, fixed_band);
    }
    for (std::size_t l = 0; l < config.lines.size(); ++l) {
      const auto& c = counts.lines[l];
      std::string compared;
      if (options.reference) {
        const auto& r = truth.lines[l];
        compared = fmt::format(" {:>6} {:>6}", r.in, r.out);
        total_error +=
            std::labs(static_cast<long>(c.in - r.in)) + std::labs(static_cast<long>(c.out - r.out));
        total_reference += static_cast<long>(r.in + r.out);
      }
      fmt::print("{:<16} {:<10} {:>6} {:>6}{}\n", sequence.info.name, config.lines[l].name, c.in,
                 c.out, compared);
    }
    spdlog::debug("{}: box noise {:.4f} of the box height", sequence.info.name, counts.box_noise);
    for (std::size_t z = 0; z < config.zones.size(); ++z) {
      const auto& c = counts.zones[z];
      fmt::print("{:<16} {:<10} entered {} exited {} (lost inside {}) dwelled {}\n",
                 sequence.info.name, config.zones[z].name, c.entered, c.exited, c.lost_inside,
                 c.dwelled);
    }
  }
  if (options.reference) {
    fmt::print("TOTAL absolute count error {} of {} reference crossings: {}\n", total_error,
               total_reference, percent(total_error, total_reference));
  }
  return to_int(ExitCode::ok);
}

}  // namespace

Subcommand add_count_command(CLI::App& parent) {
  auto options = std::make_shared<CountCommandOptions>();
  CLI::App* cli = parent.add_subcommand(
      "count",
      "Count line crossings and zone visits on MOTChallenge sequences (tracker results or ground "
      "truth); --reference compares with the ground truth counted at every frame");
  cli->add_option("--dataset", options->dataset,
                  "a sequence folder (with seqinfo.ini) or a folder of them")
      ->required();
  cli->add_option("--lines", options->lines_file,
                  "YAML: sequences: {<name>: <events section: lines, zones>} (docs/events.md)")
      ->required();
  cli->add_option("--tracks", options->tracks_dir,
                  "folder of results files <sequence>.txt (rtmot track --out); absent: count the "
                  "ground truth gt/gt.txt");
  cli->add_option("--interval", options->interval,
                  "count frames 1, 1+N, 1+2N, ... only (the ground truth kept where a tracker "
                  "skipping frames would run)")
      ->check(integer_in(1, motio::kMaxFrame))
      ->capture_default_str();
  cli->add_flag("--reference", options->reference,
                "compare every count with the ground truth counted at every frame");
  return {cli, [options] { return run_count(*options); }};
}

}  // namespace rtmot::app
