// Cross-validation on two real MOT15 sequences and two detectors: each fold's choice is the best
// candidate on what the fold may see, and the held-out table is exactly that choice's score on
// what the fold left out.
#include "study/study_cv.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <mutex>

#include "mot/metrics.hpp"
#include "shared_data.hpp"
#include "study/run_progress.hpp"
#include "tracker/presets.hpp"

namespace rtmot::study {
namespace {

namespace fs = std::filesystem;

std::vector<LoadedSequence> two_sequences() {
  const fs::path dir = fs::temp_directory_path() / ("rtmot-cv-test-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  for (const char* name : {"TUD-Campus", "TUD-Stadtmitte"}) {
    const fs::path link = dir / name;
    if (!fs::exists(link))
      fs::create_directory_symlink(test::shared_path("data/mot15-train") / name, link);
  }
  auto dataset = load_study_dataset(dir);
  fs::remove_all(dir);
  return dataset;
}

mot::SequenceCounts score_counts(const LoadedSequence& sequence, StudyInput input,
                                 const StudyConfiguration& c, int interval) {
  return track_and_count(sequence, input, c.config, interval, c.knobs);
}

mot::Metrics score(const std::vector<const LoadedSequence*>& sequences, StudyInput input,
                   const StudyConfiguration& c, int interval) {
  mot::SequenceCounts total;
  for (const auto* s : sequences) total += track_and_count(*s, input, c.config, interval, c.knobs);
  return mot::summarize(total);
}

TEST(CrossValidation, FoldsChooseOnWhatTheyMaySeeAndScoreWhatTheyLeftOut) {
  RTMOT_REQUIRE_FILE(test::shared_path("data/mot15-train/TUD-Stadtmitte"));
  const auto dataset = two_sequences();
  ASSERT_EQ(dataset.size(), 2U);
  const auto candidates = cv_candidates(true);
  ASSERT_GE(candidates.size(), 2U);
  const std::vector<StudyInput> inputs = {StudyInput::detections,
                                          StudyInput::synthetic_detector(0)};
  const std::vector<int> intervals = {1, 5};
  // Progress: every run reported once, from the workers, counting up to all of them.
  std::mutex progress_mutex;
  std::vector<std::size_t> reported;
  std::size_t reported_total = 0;
  const CrossValidation cv =
      cross_validate(dataset, candidates, inputs, intervals, 2, nullptr, {},
                     [&](std::size_t done, std::size_t total) {
                       const std::lock_guard<std::mutex> lock(progress_mutex);
                       reported.push_back(done);
                       reported_total = total;
                     });
  const std::size_t runs = candidates.size() * inputs.size() * intervals.size() * dataset.size();
  EXPECT_EQ(reported_total, runs);
  ASSERT_EQ(reported.size(), runs);
  std::sort(reported.begin(), reported.end());
  for (std::size_t i = 0; i < runs; ++i) EXPECT_EQ(reported[i], i + 1);

  ASSERT_EQ(cv.folds.size(), 4U);
  ASSERT_EQ(cv.tables.size(), 4U);  // held-out and in-sample, per detector
  const auto find = [&](const std::string& name) {
    for (const auto& c : candidates) {
      if (c.name == name) return c;
    }
    ADD_FAILURE() << name;
    return candidates.front();
  };

  // The fold that leaves out TUD-Campus through the public detections sees only TUD-Stadtmitte
  // through the synthetic detector: its choice must be the best there.
  const FoldChoice& fold = cv.folds[0];
  EXPECT_EQ(fold.held_out, "TUD-Campus");
  EXPECT_EQ(fold.detector, "det");
  double best = -1e300;
  std::string best_name;
  for (const auto& c : candidates) {
    std::vector<mot::Metrics> by_interval;
    for (const int i : intervals) by_interval.push_back(score({&dataset[1]}, inputs[1], c, i));
    const double s = selection_score(by_interval);
    if (s > best) best = s, best_name = c.name;
  }
  EXPECT_EQ(fold.chosen, best_name);

  // The held-out table on det pools each fold's choice on its own left-out sequence.
  const StudyTable& held_out = cv.tables[0];
  EXPECT_EQ(held_out.configuration.name, "cv-held-out");
  EXPECT_EQ(held_out.input, StudyInput::detections);
  for (std::size_t i = 0; i < intervals.size(); ++i) {
    mot::SequenceCounts total =
        score_counts(dataset[0], inputs[0], find(cv.folds[0].chosen), intervals[i]);
    total += score_counts(dataset[1], inputs[0], find(cv.folds[1].chosen), intervals[i]);
    const mot::Metrics expected = mot::summarize(total);
    EXPECT_DOUBLE_EQ(held_out.rows[i].metrics.mota, expected.mota);
    EXPECT_DOUBLE_EQ(held_out.rows[i].metrics.idf1, expected.idf1);
  }
  EXPECT_FALSE(format_folds_markdown(cv).empty());
}

// With references, a fold chooses the candidate that holds the most (detector, interval) cells
// against every reference in MOTA and IDF1, and only then the best mean; the in-sample table of
// cells held is recounted here from separate runs.
TEST(CrossValidation, WithReferencesTheMostCellsHeldComeBeforeTheMean) {
  RTMOT_REQUIRE_FILE(test::shared_path("data/mot15-train/TUD-Stadtmitte"));
  const auto dataset = two_sequences();
  ASSERT_EQ(dataset.size(), 2U);
  // ByteTrack itself is a candidate: it holds every cell against itself, and SORT is below it on
  // these two sequences at both intervals (checked below), whatever its mean.
  std::vector<StudyConfiguration> candidates = cv_candidates(true);
  candidates.push_back({"bytetrack-again", "cv", *tracker::find_preset("bytetrack")});
  const std::vector<StudyConfiguration> references = {
      {"preset-bytetrack", "cv", *tracker::find_preset("bytetrack")},
      {"preset-sort", "cv", *tracker::find_preset("sort")}};
  const std::vector<StudyInput> inputs = {StudyInput::detections,
                                          StudyInput::synthetic_detector(0)};
  const std::vector<int> intervals = {1, 5};
  const CrossValidation cv =
      cross_validate(dataset, candidates, inputs, intervals, 2, nullptr, references);

  const auto held_and_mean = [&](const std::vector<const LoadedSequence*>& sequences,
                                 const std::vector<StudyInput>& seen,
                                 const StudyConfiguration& config) {
    int held = 0;
    std::vector<mot::Metrics> pooled_by_interval;
    for (const int i : intervals) {
      mot::SequenceCounts pooled;
      for (const StudyInput input : seen) {
        const mot::Metrics mine = score(sequences, input, config, i);
        bool holds = true;
        for (const auto& r : references) {
          const mot::Metrics theirs = score(sequences, input, r, i);
          holds = holds && mine.mota >= theirs.mota && mine.idf1 >= theirs.idf1;
        }
        held += holds ? 1 : 0;
        for (const auto* s : sequences) pooled += score_counts(*s, input, config, i);
      }
      pooled_by_interval.push_back(mot::summarize(pooled));
    }
    return std::pair{held, selection_score(pooled_by_interval)};
  };

  // Fold 0 sees TUD-Stadtmitte through the synthetic detector only.
  std::pair<int, double> best{-1, -1e300};
  std::string best_name;
  for (const auto& c : candidates) {
    const auto mine = held_and_mean({&dataset[1]}, {inputs[1]}, c);
    if (mine > best) best = mine, best_name = c.name;
  }
  EXPECT_EQ(cv.folds[0].chosen, best_name);
  EXPECT_EQ(best.first, 2);  // bytetrack-again holds both cells, so the choice must too

  ASSERT_EQ(cv.in_sample_scores.size(), candidates.size());
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    const auto expected = held_and_mean({&dataset[0], &dataset[1]}, inputs, candidates[c]);
    EXPECT_EQ(cv.in_sample_scores[c].cells_held, expected.first) << candidates[c].name;
    EXPECT_NEAR(cv.in_sample_scores[c].mean, expected.second, 1e-9) << candidates[c].name;
  }
  EXPECT_EQ(cv.in_sample_scores.back().cells_held, 4);
}

// What `rtmot study` prints while the cross-validation runs (apps/cmd_study.cpp).
TEST(RunProgressLine, SaysHowFarAndTheTimeLeftAtThePaceSoFar) {
  EXPECT_EQ(run_progress_line(120, 600, 30.0), "run 120 of 600 (20%) | ETA 2:00");
  EXPECT_EQ(run_progress_line(1, 3, 0.4), "run 1 of 3 (33%) | ETA 0:01");
  EXPECT_EQ(run_progress_line(0, 600, 0.0), "run 0 of 600 (0%)");
  EXPECT_EQ(run_progress_line(600, 600, 150.0), "run 600 of 600 (100%)");
}

TEST(CrossValidation, AStopBeforeItStartsGivesAnEmptyResultAtOnce) {
  RTMOT_REQUIRE_FILE(test::shared_path("data/mot15-train/TUD-Stadtmitte"));
  const auto dataset = two_sequences();
  const std::atomic<bool> stop{true};
  const CrossValidation cv =
      cross_validate(dataset, cv_candidates(true), {StudyInput::detections}, {1, 5}, 2, &stop);
  EXPECT_TRUE(cv.folds.empty());
  EXPECT_TRUE(cv.tables.empty());
  EXPECT_TRUE(cv.in_sample_choice.empty());
}

}  // namespace
}  // namespace rtmot::study
