// The tracker's use of appearance (tracker/appearance.hpp): the distance and the model's update,
// and a crossing that boxes alone get wrong.
#include <gtest/gtest.h>

#include <map>

#include "scene.hpp"
#include "tracker/appearance.hpp"
#include "tracker/presets.hpp"
#include "tracker/tracker.hpp"

namespace rtmot::tracker {
namespace {

// All the weight in one bin: two colours with nothing in common.
Appearance colour(int bin) {
  Appearance appearance;
  appearance.bins[static_cast<std::size_t>(bin)] = 1.F;
  appearance.valid = true;
  return appearance;
}

TEST(Appearance, HellingerDistanceIsZeroForEqualAndOneForDisjointHistograms) {
  EXPECT_FLOAT_EQ(appearance_distance(colour(3), colour(3)), 0.F);
  EXPECT_FLOAT_EQ(appearance_distance(colour(3), colour(7)), 1.F);
  Appearance half = colour(3);
  half.bins[3] = 0.5F;
  half.bins[7] = 0.5F;
  // Bhattacharyya coefficient sqrt(0.5): distance sqrt(1 - 0.7071).
  EXPECT_NEAR(appearance_distance(half, colour(3)), 0.5412, 1e-4);
}

TEST(Appearance, TheModelMovesTowardsWhatIsSeenByOneMinusTheMomentum) {
  Appearance model;
  blend_appearance(model, colour(2), 0.9F);  // an empty model takes the first sighting
  EXPECT_TRUE(model.valid);
  EXPECT_FLOAT_EQ(model.bins[2], 1.F);
  blend_appearance(model, colour(5), 0.9F);
  EXPECT_FLOAT_EQ(model.bins[2], 0.9F);
  EXPECT_FLOAT_EQ(model.bins[5], 0.1F);
}

// Two people walk towards each other, meet (one box for both: the detector sees one of them), and
// turn back where they came from. The constant-velocity prediction carries each across, onto the
// other: boxes alone swap their ids. Their colours (red and blue) do not.
std::map<int, int> ids_by_colour(const TrackerConfig& config, bool with_colours) {
  Tracker tracker(config);
  const Appearance red = colour(0);
  const Appearance blue = colour(30);
  std::map<int, int> last_id;  // colour bin -> id reported on the last frame
  const auto seen = [&](float x, const Appearance& look) {
    Detection d = test::detection(x, 200.F);
    if (with_colours) d.appearance = look;
    return d;
  };
  int frame = 0;
  const auto step = [&](const std::vector<Detection>& detections) {
    return tracker.update(detections, frame++ / config.frame_rate);
  };
  for (int i = 0; i < 10; ++i) step({seen(100.F + 20.F * i, red), seen(460.F - 20.F * i, blue)});
  step({seen(290.F, red)});  // together: one box
  for (int i = 1; i <= 8; ++i) {
    const float red_x = 290.F - 20.F * i;
    const float blue_x = 290.F + 20.F * i;
    const auto& reports = step({seen(red_x, red), seen(blue_x, blue)});
    for (const TrackReport& r : reports) last_id[r.box.center_x() < 290.F ? 0 : 30] = r.id;
  }
  return last_id;
}

TEST(Appearance, IdsFollowTheColoursThroughACrossingThatBoxesAloneSwap) {
  TrackerConfig config = *find_preset("rtmot");
  config.appearance_gate = 0.8;
  config.appearance_weight = 0.5;
  // The first frames' ids: red started first (id 1), blue second (id 2).
  const auto boxes_only = ids_by_colour(config, false);
  ASSERT_EQ(boxes_only.size(), 2U);
  EXPECT_EQ(boxes_only.at(0), 2) << "without colours the red person should take blue's id";
  const auto with_colours = ids_by_colour(config, true);
  ASSERT_EQ(with_colours.size(), 2U);
  EXPECT_EQ(with_colours.at(0), 1);
  EXPECT_EQ(with_colours.at(30), 2);
}

}  // namespace
}  // namespace rtmot::tracker
