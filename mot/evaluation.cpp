#include "mot/evaluation.hpp"

#include <algorithm>

#include "common/input_error.hpp"
#include "motio/mot_files.hpp"
#include "mot/prepared_sequence.hpp"
#include "mot/scorer.hpp"

namespace rtmot::mot {

namespace fs = std::filesystem;

std::vector<fs::path> find_sequence_dirs(const fs::path& dir) {
  if (!fs::is_directory(dir)) throw InputError(dir.string(), 0, "", "is not a folder");
  if (fs::exists(dir / "seqinfo.ini")) return {dir};
  std::vector<fs::path> sequences;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.is_directory() && fs::exists(entry.path() / "seqinfo.ini")) {
      sequences.push_back(entry.path());
    }
  }
  if (sequences.empty()) {
    throw InputError(dir.string(), 0, "", "holds no sequence folder (one with a seqinfo.ini)");
  }
  std::sort(sequences.begin(), sequences.end());
  return sequences;
}

SequenceScore evaluate_sequence(const fs::path& sequence_dir, const fs::path& results_file,
                                int interval) {
  const motio::SequenceInfo info = motio::read_seqinfo(sequence_dir / "seqinfo.ini");
  const fs::path gt_file = sequence_dir / "gt" / "gt.txt";
  if (!fs::exists(results_file)) {
    throw InputError(results_file.string(), 0, "", "missing: no results for sequence " + info.name);
  }
  const auto gt_rows = motio::read_mot_file(gt_file, motio::MotFileKind::ground_truth, info.length);
  const auto result_rows = motio::read_mot_file(results_file, motio::MotFileKind::results, info.length);
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

EvaluationReport evaluate(const fs::path& gt_dir, const fs::path& results_dir, int interval) {
  if (!fs::is_directory(results_dir)) {
    throw InputError(results_dir.string(), 0, "", "is not a folder");
  }
  EvaluationReport report;
  for (const auto& sequence_dir : find_sequence_dirs(gt_dir)) {
    const std::string name = motio::read_seqinfo(sequence_dir / "seqinfo.ini").name;
    report.sequences.push_back(
        evaluate_sequence(sequence_dir, results_dir / (name + ".txt"), interval));
  }
  report.overall = pool(report.sequences);
  return report;
}

}  // namespace rtmot::mot
