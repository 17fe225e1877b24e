// The detector's own cut on a real MOT15 sequence's synthetic SSD: a lower cut keeps more of the
// detector's detections, a cut below its floor keeps all of them and tracks exactly as the
// synthetic detector itself, and no held-back detector may be used to choose a cut.
#include "study/detector_cut.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>

#include "shared_data.hpp"
#include "study/synthetic_detector.hpp"
#include "tracker/presets.hpp"

namespace rtmot::study {
namespace {

int index_of(const std::string& name) {
  const auto& specs = synthetic_detectors();
  for (std::size_t i = 0; i < specs.size(); ++i) {
    if (specs[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

TEST(DetectorCut, ALowerCutKeepsMoreAndNoCutIsTheDetectorItself) {
  RTMOT_REQUIRE_FILE(test::shared_path("data/mot15-train/TUD-Campus/gt/gt.txt"));
  const auto dataset = load_study_dataset(test::shared_path("data/mot15-train/TUD-Campus"));
  ASSERT_EQ(dataset.size(), 1U);
  // synth-ssd's scores are sigmoid(z - 1) with z >= -1: all at least 0.119.
  const std::vector<float> cuts = {0.5F, 0.3F, 0.1F};
  const auto tables = run_detector_cut_sweep(dataset, {"rtmot", "sort"}, "synth-ssd", cuts, {1, 5});
  ASSERT_EQ(tables.size(), 2U);
  for (const auto& table : tables) {
    ASSERT_EQ(table.rows.size(), cuts.size());
    EXPECT_LT(table.rows[0].kept_share, table.rows[1].kept_share);
    EXPECT_LT(table.rows[1].kept_share, table.rows[2].kept_share);
    EXPECT_GT(table.rows[0].kept_share, 0.3);  // true detections score high on this detector
    EXPECT_DOUBLE_EQ(table.rows[2].kept_share, 1.0);
    ASSERT_EQ(table.rows[2].by_interval.size(), 2U);
    const auto uncut =
        track_and_score(dataset, StudyInput::synthetic_detector(index_of("synth-ssd")),
                        *tracker::find_preset(table.preset), 5, {});
    EXPECT_DOUBLE_EQ(table.rows[2].by_interval[1].mota, uncut.mota) << table.preset;
    EXPECT_DOUBLE_EQ(table.rows[2].by_interval[1].idf1, uncut.idf1) << table.preset;
  }
  const std::string markdown = format_detector_cut_markdown(tables, {1, 5});
  EXPECT_NE(markdown.find("| rtmot | synth-ssd | 0.5 |"), std::string::npos) << markdown;
  EXPECT_NE(markdown.find("N = 5 MOTA / IDF1"), std::string::npos) << markdown;
}

TEST(DetectorCut, HeldBackOrUnknownDetectorsAreRefused) {
  RTMOT_REQUIRE_FILE(test::shared_path("data/mot15-train/TUD-Campus/gt/gt.txt"));
  const auto dataset = load_study_dataset(test::shared_path("data/mot15-train/TUD-Campus"));
  EXPECT_THROW(run_detector_cut_sweep(dataset, {"rtmot"}, "holdout-o", {0.3F}, {1}),
               std::invalid_argument);
  EXPECT_THROW(run_detector_cut_sweep(dataset, {"rtmot"}, "no-such", {0.3F}, {1}),
               std::invalid_argument);
  EXPECT_THROW(run_detector_cut_sweep(dataset, {"no-such-preset"}, "synth-ssd", {0.3F}, {1}),
               std::invalid_argument);
}

}  // namespace
}  // namespace rtmot::study
