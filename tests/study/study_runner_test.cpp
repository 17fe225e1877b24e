// The thread pool must give the same numbers as running each configuration alone.
#include "study/study_runner.hpp"

#include <gtest/gtest.h>

#include <atomic>

#include "shared_data.hpp"

namespace rtmot::study {
namespace {

TEST(StudyRunner, ParallelRunsEqualSerialScoresOnARealSequence) {
  const auto sequence = test::shared_path("data/mot15-train/TUD-Campus");
  RTMOT_REQUIRE_FILE(sequence);
  const auto dataset = load_study_dataset(sequence);
  ASSERT_EQ(dataset.size(), 1U);
  const auto configurations = study_configurations(true);
  ASSERT_GE(configurations.size(), 3U);
  const std::vector<StudyConfiguration> some(configurations.begin(), configurations.begin() + 3);
  std::atomic<int> calls{0};
  const auto tables = run_study(dataset, some, {StudyInput::detections, StudyInput::ground_truth},
                                {1, 5}, 2, [&](int, int total, const StudyTable&, int) {
                                  EXPECT_EQ(total, 3 * 2 * 2);
                                  ++calls;
                                });
  EXPECT_EQ(calls.load(), 12);
  ASSERT_EQ(tables.size(), 6U);
  for (const auto& table : tables) {
    ASSERT_EQ(table.rows.size(), 2U);
    for (const auto& row : table.rows) {
      const mot::Metrics alone = track_and_score(dataset, table.input, table.configuration.config,
                                                 row.interval, table.configuration.knobs);
      EXPECT_EQ(row.metrics.false_positives, alone.false_positives);
      EXPECT_EQ(row.metrics.id_switches, alone.id_switches);
      EXPECT_DOUBLE_EQ(row.metrics.mota, alone.mota);
    }
  }
  // A perfect detector beats the public detections at full rate.
  EXPECT_GT(tables[1].rows[0].metrics.mota, tables[0].rows[0].metrics.mota);
}

// A stop (SIGINT/SIGTERM in `rtmot study`) is seen by every worker before its next run: runs in
// progress finish, none starts after it.
TEST(StudyRunner, AStopEndsTheRunsEarly) {
  const auto sequence = test::shared_path("data/mot15-train/TUD-Campus");
  RTMOT_REQUIRE_FILE(sequence);
  const auto dataset = load_study_dataset(sequence);
  const auto configurations = study_configurations(true);
  std::atomic<bool> stop{false};
  std::atomic<int> calls{0};
  const int total = static_cast<int>(configurations.size()) * 2 * 3;
  run_study(
      dataset, configurations, {StudyInput::detections, StudyInput::ground_truth}, {1, 5, 10}, 2,
      [&](int, int, const StudyTable&, int) {
        if (++calls == 3) stop = true;
      },
      &stop);
  EXPECT_GE(calls.load(), 3);
  EXPECT_LE(calls.load(), 4) << "at most the other worker's run in progress finishes";
  EXPECT_GT(total, 20);
}

}  // namespace
}  // namespace rtmot::study
