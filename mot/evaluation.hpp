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
  /// N when every result row is on frames 1, 1 + N, 1 + 2N, ... (N >= 2, at least 3 such frames):
  /// results of a run that processed every Nth frame; 1 otherwise.
  int results_every{1};
};

/// Which frames are scored: every `interval`-th, or with `processed_frames` the frames listed in
/// the results' <sequence>.frames files (motio/processed_frames.hpp).
struct EvaluationScope {
  int interval{1};
  bool processed_frames{false};
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
/// The same on the frames listed in `frames_file` (motio/processed_frames.hpp); a missing file is
/// an InputError naming it.
SequenceScore evaluate_sequence_on_frames(const std::filesystem::path& sequence_dir,
                                          const std::filesystem::path& results_file,
                                          const std::filesystem::path& frames_file);

/// Pools per-sequence scores into the OVERALL line.
SequenceScore pool(const std::vector<SequenceScore>& sequences);

/// Every sequence under `gt_dir` (motio::find_sequences) against `results_dir`/<name>.txt. A
/// missing results file is an InputError naming it. A set `stop` flag ends it before the next
/// sequence; `progress` is called after each scored one.
EvaluationReport evaluate(const std::filesystem::path& gt_dir,
                          const std::filesystem::path& results_dir, int interval = 1,
                          const std::atomic<bool>* stop = nullptr,
                          const std::function<void(const SequenceScore&)>& progress = {});
EvaluationReport evaluate(const std::filesystem::path& gt_dir,
                          const std::filesystem::path& results_dir, const EvaluationScope& scope,
                          const std::atomic<bool>* stop = nullptr,
                          const std::function<void(const SequenceScore&)>& progress = {});

}  // namespace rtmot::mot
