#pragma once
// Scoring result files against MOTChallenge ground truth: the file side of `rtmot eval`.
#include <filesystem>
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
};

/// `dir` itself if it holds a seqinfo.ini, else its sub-folders that do (sorted by name). Throws
/// InputError if there is none.
std::vector<std::filesystem::path> find_sequence_dirs(const std::filesystem::path& dir);

/// Scores one results file against `sequence_dir`/gt/gt.txt (frames as its seqinfo.ini).
SequenceScore evaluate_sequence(const std::filesystem::path& sequence_dir,
                                const std::filesystem::path& results_file, int interval = 1);

/// Pools per-sequence scores into the OVERALL line.
SequenceScore pool(const std::vector<SequenceScore>& sequences);

/// Every sequence under `gt_dir` against `results_dir`/<name>.txt. A missing results file is an
/// InputError naming it.
EvaluationReport evaluate(const std::filesystem::path& gt_dir,
                          const std::filesystem::path& results_dir, int interval = 1);

}  // namespace rtmot::mot
