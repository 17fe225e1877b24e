#include "study/study_report.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

namespace rtmot::study {
namespace {

StudyTable example_table() {
  StudyTable table;
  table.configuration = {"kalman-iou", "grid", tracker::TrackerConfig::sort_preset()};
  table.input = StudyInput::detections;
  StudyRow full{1, {}};
  full.metrics.mota = 39.94;
  full.metrics.idf1 = 45.86;
  full.metrics.gt_tracks = 500;
  full.metrics.mostly_lost = 125;
  full.metrics.false_positives = 5870;
  StudyRow tenth{10, {}};
  tenth.metrics.mota = 12.0;
  tenth.metrics.gt_tracks = 500;
  tenth.metrics.mostly_lost = 400;
  table.rows = {full, tenth};
  return table;
}

TEST(StudyReport, CsvHasTheDevkitColumnsAndARowPerInterval) {
  const std::string csv = format_study_csv(example_table());
  std::istringstream lines(csv);
  std::string header, first, second, extra;
  std::getline(lines, header);
  std::getline(lines, first);
  std::getline(lines, second);
  EXPECT_FALSE(std::getline(lines, extra));
  EXPECT_EQ(header, "interval,Rcll,Prcn,FAR,GT,MT,PT,ML,FP,FN,IDs,FM,MOTA,MOTP,IDF1,HOTA");
  EXPECT_EQ(first, "1,0.0,0.0,0.00,500,0,0,125,5870,0,0,0,39.9,0.0,45.9,0.0");
  EXPECT_EQ(second.substr(0, 3), "10,");
}

TEST(StudyReport, MarkdownIsAPipeTable) {
  const std::string md = format_study_markdown(example_table());
  EXPECT_EQ(md.rfind("| interval | Rcll |", 0), 0U);
  EXPECT_NE(md.find("|---:|"), std::string::npos);
  EXPECT_NE(md.find("| 10 |"), std::string::npos);
}

TEST(StudyReport, NotMostlyLostIsTheShareOfGtTracksWithSomeCoverage) {
  EXPECT_DOUBLE_EQ(not_mostly_lost_percent(example_table().rows[0].metrics), 75.0);
  EXPECT_DOUBLE_EQ(not_mostly_lost_percent(mot::Metrics{}), 0.0);
}

TEST(StudyReport, WritesTablesPlotsAndSummary) {
  const auto out = std::filesystem::path(::testing::TempDir()) / "study_report_test";
  std::filesystem::remove_all(out);
  const auto files = write_study(out, {example_table()}, "study/");
  EXPECT_TRUE(std::filesystem::exists(out / "tables" / "det" / "kalman-iou.csv"));
  EXPECT_TRUE(std::filesystem::exists(out / "tables" / "det" / "kalman-iou.md"));
  EXPECT_TRUE(std::filesystem::exists(out / "plots" / "det-grid-mota.svg"));
  EXPECT_TRUE(std::filesystem::exists(out / "plots" / "det-grid-not-ml.svg"));
  std::ifstream summary(out / "summary.md");
  const std::string text((std::istreambuf_iterator<char>(summary)), {});
  EXPECT_NE(text.find("](study/plots/det-grid-idf1.svg)"), std::string::npos);
  EXPECT_NE(text.find("### kalman-iou on det/det.txt"), std::string::npos);
  EXPECT_EQ(files.size(), 2U + 4U + 1U);
}

}  // namespace
}  // namespace rtmot::study
