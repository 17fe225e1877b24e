// The thread pool must give the same numbers as running each configuration alone.
#include "mot/study_runner.hpp"

#include <gtest/gtest.h>

#include <atomic>

#include "shared_data.hpp"

namespace rtmot::mot {
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
      const Metrics alone =
          track_and_score(dataset, table.input, table.configuration.config, row.interval);
      EXPECT_EQ(row.metrics.false_positives, alone.false_positives);
      EXPECT_EQ(row.metrics.id_switches, alone.id_switches);
      EXPECT_DOUBLE_EQ(row.metrics.mota, alone.mota);
    }
  }
  // A perfect detector beats the public detections at full rate.
  EXPECT_GT(tables[1].rows[0].metrics.mota, tables[0].rows[0].metrics.mota);
}

}  // namespace
}  // namespace rtmot::mot
