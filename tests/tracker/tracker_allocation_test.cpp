// Steady state allocates nothing. This executable replaces the global operator new/delete to
// count allocations, warms a tracker up on the first half of a MOT15 sequence, then requires zero
// allocations over the second half, for every predictor and affinity.
#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>
#include <vector>

#include "allocation_counter.hpp"
#include "mot_detections.hpp"
#include "shared_data.hpp"
#include "tracker/presets.hpp"
#include "tracker/tracker.hpp"

namespace rtmot::tracker {
namespace {

class SteadyState : public ::testing::TestWithParam<std::tuple<PredictorKind, AffinityKind>> {};

TEST_P(SteadyState, AllocatesNothingAfterWarmUp) {
  const auto dir = test::shared_path("data/mot15-train/ADL-Rundle-6");
  RTMOT_REQUIRE_FILE(dir / "det" / "det.txt");
  test::MotSequence sequence = test::load_mot_sequence(dir);
  // Each detection an appearance (one bin by where it is: no images here), so that the gate, the
  // preference and re-identification run too.
  for (auto& frame : sequence.frames) {
    for (Detection& detection : frame) {
      const auto bin = static_cast<std::size_t>(std::abs(static_cast<int>(detection.box.x)) / 64 %
                                                Appearance::kBins);
      detection.appearance.bins.fill(0.F);
      detection.appearance.bins[bin] = 1.F;
      detection.appearance.valid = true;
    }
  }
  // Every option on: they must not allocate either.
  TrackerConfig config = with_every_option(TrackerConfig::sort_preset());
  config.predictor = std::get<0>(GetParam());
  config.affinity = std::get<1>(GetParam());
  config.affinity_threshold = default_threshold(config.affinity);
  config.image_width = sequence.width;
  config.image_height = sequence.height;
  config.particle_count = 30;
  Tracker tracker(config);

  const std::size_t half = sequence.frames.size() / 2;
  long reported = 0;
  for (std::size_t f = 0; f < half; ++f) tracker.update(sequence.frames[f], 0.0);
  long during = 0;
  {
    const test::CountingScope counting;
    for (std::size_t f = half; f < sequence.frames.size(); ++f)
      reported += static_cast<long>(tracker.update(sequence.frames[f], 0.0).size());
    during = counting.allocations();
  }
  EXPECT_EQ(during, 0) << "allocations over " << sequence.frames.size() - half << " frames";
  EXPECT_GT(reported, 0);  // it did track something
}

// The default preset as `rtmot track` runs it (elapsed time steps, the relative split): the same,
// with the whole track table (every live track's stage) read after every update.
TEST(SteadyStateDefault, AllocatesNothingAfterWarmUp) {
  const auto dir = test::shared_path("data/mot15-train/ADL-Rundle-6");
  RTMOT_REQUIRE_FILE(dir / "det" / "det.txt");
  const test::MotSequence sequence = test::load_mot_sequence(dir);
  TrackerConfig config = *find_preset(default_preset_name());
  config.frame_rate = 30.0;
  Tracker tracker(config);
  const std::size_t half = sequence.frames.size() / 2;
  for (std::size_t f = 0; f < half; ++f) {
    tracker.update(sequence.frames[f], f / 30.0);
    tracker.track_table();
  }
  long reported = 0;
  long live = 0;
  long during = 0;
  {
    const test::CountingScope counting;
    for (std::size_t f = half; f < sequence.frames.size(); ++f) {
      reported += static_cast<long>(tracker.update(sequence.frames[f], f / 30.0).size());
      live += static_cast<long>(tracker.track_table().size());
    }
    during = counting.allocations();
  }
  EXPECT_EQ(during, 0);
  EXPECT_GT(reported, 0);
  EXPECT_GT(live, reported);  // the table holds the unreported tracks too
}

// Full-rate output: the predictions for the skipped frames between updates (every 5th frame
// processed) write into the caller's reserved buffer and allocate nothing either.
TEST(SteadyStatePredictions, AllocatesNothingAfterWarmUp) {
  const auto dir = test::shared_path("data/mot15-train/ADL-Rundle-6");
  RTMOT_REQUIRE_FILE(dir / "det" / "det.txt");
  const test::MotSequence sequence = test::load_mot_sequence(dir);
  TrackerConfig config = *find_preset(default_preset_name());
  config.frame_rate = 30.0;
  Tracker tracker(config);
  std::vector<TrackReport> predicted;
  predicted.reserve(static_cast<std::size_t>(config.max_tracks));
  const std::size_t half = sequence.frames.size() / 2;
  long boxes = 0;
  long during = 0;
  for (std::size_t f = 0; f < sequence.frames.size(); f += 5) {
    const test::CountingScope counting;
    tracker.update(sequence.frames[f], f / 30.0);
    for (std::size_t skipped = f + 1; skipped < f + 5; ++skipped) {
      tracker.predict_reported_at(skipped / 30.0, predicted);
      boxes += static_cast<long>(predicted.size());
    }
    if (f >= half) during += counting.allocations();
  }
  EXPECT_EQ(during, 0);
  EXPECT_GT(boxes, 0);
}

// Following the image (the pipeline's observed boxes): an update that first corrects the
// followed tracks' priors allocates nothing either.
TEST(SteadyStateObserved, AllocatesNothingAfterWarmUp) {
  const auto dir = test::shared_path("data/mot15-train/PETS09-S2L1");
  RTMOT_REQUIRE_FILE(dir / "det" / "det.txt");
  const test::MotSequence sequence = test::load_mot_sequence(dir);
  TrackerConfig config = *find_preset(default_preset_name());
  config.frame_rate = 7.0;
  Tracker tracker(config);
  std::vector<ObservedBox> observed;
  observed.reserve(static_cast<std::size_t>(config.max_tracks));
  const std::size_t half = sequence.frames.size() / 2;
  long during = 0;
  long corrected = 0;
  for (std::size_t f = 0; f < sequence.frames.size(); f += 3) {
    const test::CountingScope counting;
    const auto& reports = tracker.update(sequence.frames[f], f / 7.0, observed);
    // The next update's observations: each reported track a little to the right, as an image
    // would show a walker (a copy within the reserved capacity).
    observed.clear();
    for (const TrackReport& track : reports) {
      Box moved = track.box;
      moved.x += 3.F;
      observed.push_back({track.id, moved});
    }
    corrected += static_cast<long>(observed.size());
    if (f >= half) during += counting.allocations();
  }
  EXPECT_EQ(during, 0);
  EXPECT_GT(corrected, 0);
}

TEST(AllocationCounter, CountsAllocations) {
  const test::CountingScope counting;
  auto p = std::make_unique<int>(3);
  EXPECT_EQ(counting.allocations(), 1);
}

INSTANTIATE_TEST_SUITE_P(AllModels, SteadyState,
                         ::testing::Combine(::testing::ValuesIn(every_value(kPredictorNames)),
                                            ::testing::ValuesIn(every_value(kAffinityNames))),
                         [](const auto& info) {
                           return std::string(kPredictorNames.name(std::get<0>(info.param))) + "_" +
                                  std::string(kAffinityNames.name(std::get<1>(info.param)));
                         });

}  // namespace
}  // namespace rtmot::tracker
