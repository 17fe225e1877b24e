// The synthetic detectors on real ground truth (MOT15's TUD-Campus): seeded (the same detections
// twice, other detections with another seed), and they make what their recipe says: the share of
// boxes missed, false positives, jitter and the score scale.
#include "study/synthetic_detector.hpp"

#include <gtest/gtest.h>

#include "motio/mot_files.hpp"
#include "shared_data.hpp"
#include "study/study_dataset.hpp"
#include "tracker/box_geometry.hpp"

namespace rtmot::study {
namespace {

struct Truth {
  motio::SequenceInfo info;
  std::vector<motio::MotRow> rows;
};

Truth campus() {
  const auto dir = test::shared_path("data/mot15-train/TUD-Campus");
  Truth truth;
  truth.info = motio::read_seqinfo(dir / "seqinfo.ini");
  truth.rows = motio::read_mot_file(dir / "gt" / "gt.txt", motio::MotFileKind::ground_truth);
  return truth;
}

bool same(const std::vector<std::vector<tracker::Detection>>& a,
          const std::vector<std::vector<tracker::Detection>>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t f = 0; f < a.size(); ++f) {
    if (a[f].size() != b[f].size()) return false;
    for (std::size_t i = 0; i < a[f].size(); ++i) {
      if (a[f][i].score != b[f][i].score || a[f][i].box.x != b[f][i].box.x) return false;
    }
  }
  return true;
}

TEST(SyntheticDetector, IsSeeded) {
  RTMOT_REQUIRE_FILE(test::shared_path("data/mot15-train/TUD-Campus/gt/gt.txt"));
  const Truth truth = campus();
  SyntheticDetectorSpec spec = synthetic_detectors().front();
  const auto once = synthesize_detections(spec, truth.rows, truth.info, 3);
  EXPECT_TRUE(same(once, synthesize_detections(spec, truth.rows, truth.info, 3)));
  EXPECT_FALSE(same(once, synthesize_detections(spec, truth.rows, truth.info, 4)));
  spec.seed += 1;
  EXPECT_FALSE(same(once, synthesize_detections(spec, truth.rows, truth.info, 3)));
}

TEST(SyntheticDetector, MakesWhatItsRecipeSays) {
  RTMOT_REQUIRE_FILE(test::shared_path("data/mot15-train/TUD-Campus/gt/gt.txt"));
  const Truth truth = campus();
  SyntheticDetectorSpec spec;
  spec.miss_rate = 0.3;
  spec.miss_run_frames = 4.0;
  spec.false_per_frame = 2.0;
  spec.clutter_sites = 0;
  spec.jitter = 0.05;
  spec.latent_floor = -100.0;  // nothing below the detector's own threshold: counts stay exact
  spec.scale = ScoreScale::dpm;
  const auto frames = synthesize_detections(spec, truth.rows, truth.info, 0);
  ASSERT_EQ(frames.size(), static_cast<std::size_t>(truth.info.length));

  // A detection is a hit when it overlaps a ground-truth box of its frame well.
  long long truths = 0, hits = 0, detections = 0;
  double hit_score = 0.0, false_score = 0.0;
  for (int f = 1; f <= truth.info.length; ++f) {
    const auto& found = frames[static_cast<std::size_t>(f - 1)];
    detections += static_cast<long long>(found.size());
    std::vector<bool> matched(found.size(), false);
    for (const auto& row : truth.rows) {
      if (row.frame != f || row.conf == 0.F) continue;
      ++truths;
      for (std::size_t i = 0; i < found.size(); ++i) {
        if (!matched[i] && tracker::iou(found[i].box, row.box) > 0.6F) {
          matched[i] = true;
          ++hits;
          hit_score += found[i].score;
          break;
        }
      }
    }
    for (std::size_t i = 0; i < found.size(); ++i) {
      if (!matched[i]) false_score += found[i].score;
    }
  }
  const long long falses = detections - hits;
  EXPECT_NEAR(1.0 - static_cast<double>(hits) / static_cast<double>(truths), 0.3, 0.08);
  EXPECT_NEAR(static_cast<double>(falses) / truth.info.length, 2.0, 0.4);
  // DPM-like margins: true positives score higher, and the scale is not [0, 1].
  EXPECT_GT(hit_score / static_cast<double>(hits), false_score / static_cast<double>(falses) + 1.0);
  EXPECT_GT(hit_score / static_cast<double>(hits), 1.0);
}

// The study's log names a held-back detector's runs but never their scores (apps/cmd_study.cpp):
// the test is which inputs count as held back.
TEST(SyntheticDetector, HeldBackInputsAreExactlyTheHoldoutRecipes) {
  const auto& specs = synthetic_detectors();
  int held_back = 0;
  for (std::size_t i = 0; i < specs.size(); ++i) {
    const auto input = StudyInput::synthetic_detector(static_cast<int>(i));
    EXPECT_EQ(is_held_back(input), specs[i].name.rfind("holdout-", 0) == 0) << specs[i].name;
    held_back += is_held_back(input) ? 1 : 0;
  }
  EXPECT_EQ(held_back, static_cast<int>(held_back_inputs().size()));
  EXPECT_GE(held_back, 22);  // holdout-a..v
  EXPECT_FALSE(is_held_back(StudyInput::detections));
  EXPECT_FALSE(is_held_back(StudyInput::ground_truth));
}

}  // namespace
}  // namespace rtmot::study
