#include "mot/evaluation.hpp"

#include <algorithm>

#include "common/input_error.hpp"
#include "mot/prepared_sequence.hpp"
#include "mot/scorer.hpp"
#include "motio/mot_files.hpp"
#include "motio/sequence_folders.hpp"

namespace rtmot::mot {

namespace fs = std::filesystem;

SequenceScore evaluate_sequence(const fs::path& sequence_dir, const fs::path& results_file,
                                int interval) {
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
  options.sequence_length = info.length;
  options.gt_file = gt_file.string();
  options.results_file = results_file.string();
  const PreparedSequence prepared = prepare_sequence(gt_rows, result_rows, options);

  SequenceScore score;
  score.name = info.name;
  score.counts = count_all(prepared);
  score.metrics = summarize(score.counts);
  return score;
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
    report.sequences.push_back(evaluate_sequence(
        sequence.dir, motio::sequence_file(results_dir, sequence.info.name, ".txt"), interval));
    if (progress) progress(report.sequences.back());
  }
  report.overall = pool(report.sequences);
  return report;
}

}  // namespace rtmot::mot
