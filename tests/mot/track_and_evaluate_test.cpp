// The file side of `rtmot track` / `rtmot eval` through the library.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "common/input_error.hpp"
#include "mot/evaluation.hpp"
#include "mot/prepared_sequence.hpp"
#include "mot/scorer.hpp"
#include "motio/results_writer.hpp"
#include "motio/track_runner.hpp"
#include "shared_data.hpp"
#include "tracker/presets.hpp"

namespace rtmot::mot {
namespace {

namespace fs = std::filesystem;

fs::path sequence(const std::string& name) {
  return test::shared_path("data/mot15-train/" + name);
}

TEST(TrackSequence, IntervalKeepsOriginalFrameNumbers) {
  RTMOT_REQUIRE_FILE(sequence("TUD-Stadtmitte") / "seqinfo.ini");
  motio::TrackOptions options;
  options.config = *tracker::find_preset("sort");
  options.interval = 3;
  const motio::TrackRun run = motio::track_sequence(sequence("TUD-Stadtmitte"), options);
  EXPECT_EQ(run.frames_processed, (run.info.length + 2) / 3);
  ASSERT_FALSE(run.tracks.empty());
  for (const motio::MotRow& row : run.tracks) EXPECT_EQ((row.frame - 1) % 3, 0) << row.frame;
}

TEST(TrackSequence, GroundTruthAsDetectorTracksAlmostPerfectly) {
  const fs::path dir = sequence("TUD-Stadtmitte");
  RTMOT_REQUIRE_FILE(dir / "gt/gt.txt");
  motio::TrackOptions options;
  options.config = *tracker::find_preset("sort");
  options.detections = "gt/gt.txt";
  const motio::TrackRun run = motio::track_sequence(dir, options);
  PrepareOptions prepare;
  prepare.sequence_length = run.info.length;
  const auto gt = motio::read_mot_file(dir / "gt/gt.txt", motio::MotFileKind::ground_truth);
  const Metrics m = summarize(count_all(prepare_sequence(gt, run.tracks, prepare)));
  // Only SORT's start-up (min_hits) and its Kalman smoothing keep it from 100.
  EXPECT_GT(m.mota, 95.0);
  EXPECT_GT(m.idf1, 95.0);
  EXPECT_EQ(m.false_positives, 0);
}

TEST(TrackSequence, MissingDetectionsFileIsNamed) {
  motio::TrackOptions options;
  options.detections = "det/nothing-here.txt";
  try {
    motio::track_sequence(sequence("TUD-Campus"), options);
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_NE(error.file().find("nothing-here.txt"), std::string::npos) << error.what();
  }
}

class EvaluateFolders : public ::testing::Test {
 protected:
  void SetUp() override {
    results_ = fs::temp_directory_path() /
               ("rtmot_eval_" +
                std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::create_directories(results_);
  }
  void TearDown() override { fs::remove_all(results_); }
  fs::path results_;
};

TEST_F(EvaluateFolders, MissingResultsFileIsAnErrorNamingIt) {
  const fs::path fixtures = test::shared_path("data/metrics-fixtures");
  RTMOT_REQUIRE_FILE(fixtures / "TUD-Campus/result-CEM.txt");
  fs::copy_file(fixtures / "TUD-Campus/result-CEM.txt", results_ / "TUD-Campus.txt");
  try {
    evaluate(fixtures, results_);
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_EQ(error.file(), (results_ / "TUD-Stadtmitte.txt").string());
    EXPECT_NE(std::string(error.what()).find("TUD-Stadtmitte"), std::string::npos);
  }
}

TEST_F(EvaluateFolders, OverallPoolsTheSequencesCounts) {
  const fs::path fixtures = test::shared_path("data/metrics-fixtures");
  for (const char* name : {"TUD-Campus", "TUD-Stadtmitte"}) {
    RTMOT_REQUIRE_FILE(fixtures / name / "result-CEM.txt");
    fs::copy_file(fixtures / name / "result-CEM.txt", results_ / (std::string(name) + ".txt"));
  }
  const EvaluationReport report = evaluate(fixtures, results_);
  ASSERT_EQ(report.sequences.size(), 2U);
  const auto& a = report.sequences[0].metrics;
  const auto& b = report.sequences[1].metrics;
  const auto& overall = report.overall.metrics;
  EXPECT_EQ(overall.false_positives, a.false_positives + b.false_positives);
  EXPECT_EQ(overall.gt_tracks, a.gt_tracks + b.gt_tracks);
  EXPECT_EQ(overall.mostly_tracked, a.mostly_tracked + b.mostly_tracked);
  // A ratio of pooled counts lies between the sequences' ratios (HOTA, a mean of square roots
  // over alphas, need not).
  EXPECT_GE(overall.mota, std::min(a.mota, b.mota));
  EXPECT_LE(overall.mota, std::max(a.mota, b.mota));
  EXPECT_GE(overall.idf1, std::min(a.idf1, b.idf1));
  EXPECT_LE(overall.idf1, std::max(a.idf1, b.idf1));
  EXPECT_GE(overall.recall, std::min(a.recall, b.recall));
  EXPECT_LE(overall.recall, std::max(a.recall, b.recall));
}

TEST_F(EvaluateFolders, WrittenResultsScoreLikeTheRowsInMemory) {
  const fs::path dir = sequence("TUD-Campus");
  RTMOT_REQUIRE_FILE(dir / "det/det.txt");
  motio::TrackOptions options;
  options.config = *tracker::find_preset("sort");
  const motio::TrackRun run = motio::track_sequence(dir, options);
  motio::write_results(results_ / "TUD-Campus.txt", run.tracks);
  const SequenceScore from_file = evaluate_sequence(dir, results_ / "TUD-Campus.txt");
  PrepareOptions prepare;
  prepare.sequence_length = run.info.length;
  const auto gt = motio::read_mot_file(dir / "gt/gt.txt", motio::MotFileKind::ground_truth);
  const Metrics in_memory = summarize(count_all(prepare_sequence(gt, run.tracks, prepare)));
  // Two decimals in the file move IoUs by ~1e-4: the same matches here.
  EXPECT_EQ(from_file.metrics.false_positives, in_memory.false_positives);
  EXPECT_EQ(from_file.metrics.id_switches, in_memory.id_switches);
  EXPECT_NEAR(from_file.metrics.motp, in_memory.motp, 0.01);
}

}  // namespace
}  // namespace rtmot::mot
