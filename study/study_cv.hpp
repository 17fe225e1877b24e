#pragma once
// Choosing a configuration honestly: cross-validation with the study's runner, leaving out one
// sequence and one detector at a time. For each (sequence, detector), the candidate with the best
// score on the other sequences seen through the other detectors is chosen and scored on the one
// left out; the left-out scores, pooled per detector, estimate how the choice does on scenes and
// on a detector it was not chosen on (docs/study.md, "cross-validation"). With one detector it
// is leave-one-sequence-out.
// "Best" is what the product promises: with reference trackers (SORT and ByteTrack in `rtmot
// study`), first the most (detector, interval) cells in which the candidate is at least every
// reference in both MOTA and IDF1, then the highest mean (MOTA + IDF1) / 2. The mean alone is flat
// at the top (its best candidates lie within a few tenths), so it chose between near-equals by
// noise and not by whether they hold where a user would compare.
#include <functional>
#include <string>
#include <vector>

#include "study/study_dataset.hpp"
#include "study/study_plan.hpp"
#include "study/study_runner.hpp"

namespace rtmot::study {

struct FoldChoice {
  std::string held_out;  // the sequence left out
  std::string detector;  // the detector (study input) left out
  std::string chosen;    // the candidate the rest chose
};

struct CandidateScore {
  std::string name;
  int cells_held;  // (detector, interval) cells at or above every reference in MOTA and IDF1
  double mean;     // selection_score()
};

struct CrossValidation {
  /// Group "cv", per detector: "cv-held-out" (each sequence tracked by its fold's choice,
  /// pooled) and "cv-in-sample" (the choice made on everything, scored on that detector).
  std::vector<StudyTable> tables;
  std::vector<FoldChoice> folds;
  std::string in_sample_choice;
  /// Each candidate's cells held and selection score on everything, in candidate order.
  std::vector<CandidateScore> in_sample_scores;
};

/// Called after each finished run with (runs done, runs in all), from the worker threads: it must
/// be thread-safe. `rtmot study` prints a progress line with an ETA from it.
using RunProgress = std::function<void(std::size_t done, std::size_t total)>;

/// The selection score: the mean over `intervals` of (MOTA + IDF1) / 2, pooled over sequences.
double selection_score(const std::vector<mot::Metrics>& by_interval);

/// Over `dataset` (at least two sequences) and `inputs` (the detectors). Runs every candidate and
/// every reference on every sequence, detector and interval once, on `jobs` threads; without
/// references the choice is by the selection score alone. Once `stop` (may be null) is true
/// no further run starts and an empty result comes back. `progress` (may be empty) hears of
/// every finished run.
CrossValidation cross_validate(const std::vector<LoadedSequence>& dataset,
                               const std::vector<StudyConfiguration>& candidates,
                               const std::vector<StudyInput>& inputs,
                               const std::vector<int>& intervals, int jobs,
                               const std::atomic<bool>* stop = nullptr,
                               const std::vector<StudyConfiguration>& references = {},
                               const RunProgress& progress = {});

/// The folds as a Markdown table.
std::string format_folds_markdown(const CrossValidation& cv);

}  // namespace rtmot::study
