// End-to-end sanity on real MOT15 detections: plausible track counts for every predictor and
// affinity, and a reproducible particle filter. (The MOTA check belongs to the scorer's tests.)
#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "mot_detections.hpp"
#include "shared_data.hpp"
#include "tracker/tracker.hpp"

namespace rtmot::tracker {
namespace {

struct GroundTruth {
  std::set<int> ids;
  long boxes{0};
};

GroundTruth read_ground_truth(const std::filesystem::path& path) {
  GroundTruth truth;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    double v[7] = {};
    char comma = 0;
    for (int i = 0; i < 7; ++i) {
      if (i > 0) fields >> comma;
      fields >> v[i];
    }
    if (v[6] == 0.0) continue;  // rows the benchmark ignores
    truth.ids.insert(static_cast<int>(v[1]));
    ++truth.boxes;
  }
  return truth;
}

struct RunSummary {
  std::set<int> ids;
  long boxes{0};
  std::vector<TrackReport> all;
};

RunSummary run(const test::MotSequence& sequence, TrackerConfig config) {
  config.image_width = sequence.width;
  config.image_height = sequence.height;
  config.frame_rate = sequence.frame_rate;
  Tracker tracker(config);
  RunSummary summary;
  for (std::size_t f = 0; f < sequence.frames.size(); ++f) {
    for (const TrackReport& r : tracker.update(sequence.frames[f], f / sequence.frame_rate)) {
      summary.ids.insert(r.id);
      ++summary.boxes;
      summary.all.push_back(r);
    }
  }
  return summary;
}

class Mot15 : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto dir = test::shared_path("data/mot15-train/PETS09-S2L1");
    RTMOT_REQUIRE_FILE(dir / "det" / "det.txt");
    RTMOT_REQUIRE_FILE(dir / "gt" / "gt.txt");
    sequence_ = test::load_mot_sequence(dir);
    truth_ = read_ground_truth(dir / "gt" / "gt.txt");
  }
  test::MotSequence sequence_;
  GroundTruth truth_;
};

TEST_F(Mot15, EveryPredictorAndAffinityGivesPlausibleTracks) {
  ASSERT_EQ(truth_.ids.size(), 19U);  // PETS09-S2L1's ground truth
  for (const auto& [predictor, predictor_name] : kPredictorNames.entries()) {
    for (const auto& [affinity, affinity_name] : kAffinityNames.entries()) {
      TrackerConfig config = TrackerConfig::sort_preset();
      config.predictor = predictor;
      config.affinity = affinity;
      config.affinity_threshold = default_threshold(affinity);
      config.particle_count = 50;
      const RunSummary summary = run(sequence_, config);
      const std::string what = std::string(predictor_name) + "/" + std::string(affinity_name);
      // With max_age 1 every model fragments tracks (SORT itself makes about six tracks per
      // person on this scene), but each must report roughly as many boxes as people are in view.
      EXPECT_GE(summary.ids.size(), truth_.ids.size()) << what;
      EXPECT_LE(summary.ids.size(), 12 * truth_.ids.size()) << what;
      EXPECT_GT(summary.boxes, truth_.boxes * 7 / 10) << what;
      EXPECT_LT(summary.boxes, truth_.boxes * 6 / 5) << what;
    }
  }
}

TEST_F(Mot15, SortReportsMostGroundTruthBoxesWithFewIdentities) {
  const RunSummary summary = run(sequence_, TrackerConfig::sort_preset());
  EXPECT_GT(summary.boxes, truth_.boxes * 7 / 10);
  EXPECT_LE(summary.ids.size(), 7 * truth_.ids.size());
}

TEST_F(Mot15, ElapsedTimeAtTheNominalRateBehavesAsSort) {
  // Timestamps f / 7 s do not differ by exactly 1/7 s in floating point: rounding must change
  // nothing that SORT decides.
  TrackerConfig config = TrackerConfig::sort_preset();
  const RunSummary per_update = run(sequence_, config);
  config.time_step = TimeStep::elapsed;
  const RunSummary elapsed = run(sequence_, config);
  ASSERT_EQ(per_update.all.size(), elapsed.all.size());
  for (std::size_t i = 0; i < per_update.all.size(); ++i) {
    EXPECT_EQ(per_update.all[i].id, elapsed.all[i].id);
    EXPECT_NEAR(per_update.all[i].box.x, elapsed.all[i].box.x, 1e-2);
  }
}

TEST_F(Mot15, ParticleFilterIsReproducibleForASeed) {
  TrackerConfig config = TrackerConfig::sort_preset();
  config.predictor = PredictorKind::particle;
  config.particle_count = 50;
  config.seed = 42;
  const RunSummary first = run(sequence_, config);
  const RunSummary second = run(sequence_, config);
  ASSERT_EQ(first.all.size(), second.all.size());
  for (std::size_t i = 0; i < first.all.size(); ++i) {
    EXPECT_EQ(first.all[i].id, second.all[i].id);
    EXPECT_EQ(first.all[i].box.x, second.all[i].box.x);
    EXPECT_EQ(first.all[i].box.h, second.all[i].box.h);
  }
  config.seed = 43;
  const RunSummary other = run(sequence_, config);
  bool differs = other.all.size() != first.all.size();
  for (std::size_t i = 0; !differs && i < first.all.size(); ++i)
    differs = other.all[i].box.x != first.all[i].box.x;
  EXPECT_TRUE(differs);
}

}  // namespace
}  // namespace rtmot::tracker
