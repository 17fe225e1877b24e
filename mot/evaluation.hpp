#pragma once
// Scoring result files against MOTChallenge ground truth: the file side of `rtmot eval`.
#include <atomic>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "mot/metrics.hpp"
#include "mot/sequence_counts.hpp"

namespace rtmot::mot {

struct SequenceScore {
  std::string name;
  SequenceCounts counts;
  Metrics metrics;
};

struct EvaluationReport {
  std::vector<SequenceScore> sequences;
  SequenceScore overall;  // all sequences pooled, named "OVERALL"
  int sequences_in_dataset{0};
  bool stopped{false};  // by evaluate()'s stop flag: `sequences` holds the ones scored before
};

/// Scores one results file against `sequence_dir`/gt/gt.txt (frames as its seqinfo.ini).
SequenceScore evaluate_sequence(const std::filesystem::path& sequence_dir,
                                const std::filesystem::path& results_file, int interval = 1);

/// Pools per-sequence scores into the OVERALL line.
SequenceScore pool(const std::vector<SequenceScore>& sequences);

/// Every sequence under `gt_dir` (motio::find_sequences) against `results_dir`/<name>.txt. A
/// missing results file is an InputError naming it. A set `stop` flag ends it before the next
/// sequence; `progress` is called after each scored one.
EvaluationReport evaluate(const std::filesystem::path& gt_dir,
                          const std::filesystem::path& results_dir, int interval = 1,
                          const std::atomic<bool>* stop = nullptr,
                          const std::function<void(const SequenceScore&)>& progress = {});

}  // namespace rtmot::mot
