#include "mot/evaluation.hpp"

#include <algorithm>
#include <numeric>
#include <set>

#include "common/input_error.hpp"
#include "mot/prepared_sequence.hpp"
#include "mot/scorer.hpp"
#include "motio/mot_files.hpp"
#include "motio/processed_frames.hpp"
#include "motio/sequence_folders.hpp"

namespace rtmot::mot {

namespace fs = std::filesystem;

namespace {

// The largest N such that every result row is on a frame 1 + kN; 1 when fewer than 3 frames hold
// results (too few to tell a sampling from chance).
int results_every(const std::vector<motio::MotRow>& rows) {
  std::set<int> frames;
  for (const auto& row : rows) frames.insert(row.frame);
  if (frames.size() < 3) return 1;
  int step = 0;
  for (const int frame : frames) step = std::gcd(step, frame - 1);
  return std::max(step, 1);
}

SequenceScore score_sequence(const fs::path& sequence_dir, const fs::path& results_file,
                             int interval, const fs::path& frames_file) {
  const motio::SequenceInfo info = motio::read_seqinfo(sequence_dir / "seqinfo.ini");
  const fs::path gt_file = sequence_dir / "gt" / "gt.txt";
  if (!fs::exists(results_file)) {
    throw InputError(results_file.string(), 0, "", "missing: no results for sequence " + info.name);
  }
  const auto gt_rows = motio::read_mot_file(gt_file, motio::MotFileKind::ground_truth, info.length);
  const auto result_rows =
      motio::read_mot_file(results_file, motio::MotFileKind::results, info.length);
  PrepareOptions options;
  options.interval = interval;
  if (!frames_file.empty()) {
    if (!fs::exists(frames_file)) {
      throw InputError(frames_file.string(), 0, "",
                       "missing: no list of processed frames for sequence " + info.name +
                           " (rtmot track writes one beside each results file)");
    }
    options.frames = motio::read_processed_frames(frames_file, info.length);
  }
  options.sequence_length = info.length;
  options.gt_file = gt_file.string();
  options.results_file = results_file.string();
  const PreparedSequence prepared = prepare_sequence(gt_rows, result_rows, options);

  SequenceScore score;
  score.name = info.name;
  score.counts = count_all(prepared);
  score.metrics = summarize(score.counts);
  score.results_every = results_every(result_rows);
  return score;
}

}  // namespace

SequenceScore evaluate_sequence(const fs::path& sequence_dir, const fs::path& results_file,
                                int interval) {
  return score_sequence(sequence_dir, results_file, interval, {});
}

SequenceScore evaluate_sequence_on_frames(const fs::path& sequence_dir,
                                          const fs::path& results_file,
                                          const fs::path& frames_file) {
  return score_sequence(sequence_dir, results_file, 1, frames_file);
}

SequenceScore pool(const std::vector<SequenceScore>& sequences) {
  SequenceScore overall;
  overall.name = "OVERALL";
  for (const auto& sequence : sequences) overall.counts += sequence.counts;
  overall.metrics = summarize(overall.counts);
  return overall;
}

EvaluationReport evaluate(const fs::path& gt_dir, const fs::path& results_dir, int interval,
                          const std::atomic<bool>* stop,
                          const std::function<void(const SequenceScore&)>& progress) {
  return evaluate(gt_dir, results_dir, EvaluationScope{interval, false}, stop, progress);
}

EvaluationReport evaluate(const fs::path& gt_dir, const fs::path& results_dir,
                          const EvaluationScope& scope, const std::atomic<bool>* stop,
                          const std::function<void(const SequenceScore&)>& progress) {
  std::error_code error;
  if (!fs::is_directory(results_dir, error)) {
    throw InputError(results_dir.string(), 0, "", "is not a folder");
  }
  EvaluationReport report;
  const auto sequences = motio::find_sequences(gt_dir);
  report.sequences_in_dataset = static_cast<int>(sequences.size());
  for (const auto& sequence : sequences) {
    if (stop != nullptr && stop->load(std::memory_order_acquire)) {
      report.stopped = true;
      break;
    }
    const fs::path results_file = motio::sequence_file(results_dir, sequence.info.name, ".txt");
    report.sequences.push_back(
        scope.processed_frames ? evaluate_sequence_on_frames(
                                     sequence.dir, results_file,
                                     motio::processed_frames_file(results_dir, sequence.info.name))
                               : evaluate_sequence(sequence.dir, results_file, scope.interval));
    if (progress) progress(report.sequences.back());
  }
  report.overall = pool(report.sequences);
  return report;
}

}  // namespace rtmot::mot
