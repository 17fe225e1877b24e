// The tracker's use of appearance (tracker/appearance.hpp): the distance, the model's update, and
// the association's gate and preference (tracker/association.hpp) where the boxes alone would
// swap two people.
#include "tracker/appearance.hpp"

#include <gtest/gtest.h>

#include <map>
#include <vector>

#include "tracker/association.hpp"

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

// Two tracks side by side (predictions 10 px apart) and two detections, each overlapping both
// predictions: by their boxes the nearer pairs win (IoU 0.90 against 0.54), by their colours the
// other two. Whether a pair is possible stays the boxes' decision; which possible pair is taken
// is the colours' too.
struct SideBySide {
  Appearance red = colour(0);
  Appearance blue = colour(30);
  std::vector<AssociationCandidate> candidates{
      {Box{100.F, 200.F, 40.F, 80.F}, 1.0, 0.F, &red},    // 0: red
      {Box{110.F, 200.F, 40.F, 80.F}, 1.0, 0.F, &blue}};  // 1: blue
  std::vector<Detection> detections;

  explicit SideBySide(bool with_colours) {
    detections.emplace_back(Box{112.F, 200.F, 40.F, 80.F}, 0.9F, 1);  // red, nearer to blue's
    detections.emplace_back(Box{98.F, 200.F, 40.F, 80.F}, 0.9F, 1);   // blue, nearer to red's
    if (with_colours) {
      detections[0].appearance = red;
      detections[1].appearance = blue;
    }
  }

  // Leaves one detection, where the first track is predicted, looking like `look`.
  void one_detection_on_the_first_track(const Appearance& look) {
    detections.resize(1);
    detections[0].box = candidates[0].predicted;
    detections[0].appearance = look;
  }

  // candidate -> detection
  std::map<int, int> matched(const TrackerConfig& config) const {
    Associator associator(2, 2);
    std::vector<AssociationMatch> matches;
    associator.associate(config, 0.3, detections, candidates, matches);
    std::map<int, int> pairs;
    for (const AssociationMatch& m : matches) pairs[m.candidate] = m.detection;
    return pairs;
  }
};

TEST(Appearance, ColoursDecideAmongThePairsTheBoxesAllow) {
  TrackerConfig config;
  config.appearance_weight = 1.0;
  const std::map<int, int> by_boxes{{0, 1}, {1, 0}};
  const std::map<int, int> by_colours{{0, 0}, {1, 1}};
  EXPECT_EQ(SideBySide(false).matched(config), by_boxes);  // no appearance: the boxes alone
  EXPECT_EQ(SideBySide(true).matched(config), by_colours);
  config.appearance_weight = 0.0;  // off: the colours are there but play no part
  EXPECT_EQ(SideBySide(true).matched(config), by_boxes);
}

TEST(Appearance, ThePairsBeyondTheGateAreNeverMatched) {
  TrackerConfig config;
  config.appearance_gate = 0.8;  // weight 0: only the gate
  const SideBySide scene(true);
  const std::map<int, int> by_colours{{0, 0}, {1, 1}};
  EXPECT_EQ(scene.matched(config), by_colours);
  // A detection that looks like no track is matched by none, however well its box fits.
  SideBySide stranger(true);
  stranger.one_detection_on_the_first_track(colour(12));
  EXPECT_TRUE(stranger.matched(config).empty());
}

TEST(Appearance, TheContestedGateRefusesOnlyPairsWithARivalByMotion) {
  TrackerConfig config;
  config.appearance_gate = 0.8;
  config.appearance_gate_contested = true;
  // Two tracks and two detections all overlapping: every pair is contested, so the gate acts as
  // the plain one, and the colours undo what the boxes would swap.
  const std::map<int, int> by_colours{{0, 0}, {1, 1}};
  EXPECT_EQ(SideBySide(true).matched(config), by_colours);

  // One track, one detection where it is predicted, in colours the track never wore: alone on
  // both sides, the pair is matched by its motion (the plain gate refuses it).
  SideBySide changed(true);
  changed.candidates.resize(1);
  changed.one_detection_on_the_first_track(colour(12));
  EXPECT_EQ(changed.matched(config), (std::map<int, int>{{0, 0}}));
  config.appearance_gate_contested = false;
  EXPECT_TRUE(changed.matched(config).empty());
  config.appearance_gate_contested = true;

  // The same detection with a second track beside it, red like the first: the detection now has
  // two tracks its box allows, so the gate refuses both pairs.
  SideBySide rival(true);
  rival.candidates[1].appearance = &rival.red;
  rival.one_detection_on_the_first_track(colour(12));
  EXPECT_TRUE(rival.matched(config).empty());
  // ...and one that looks like the second track goes to it, though its box fits the first better.
  rival.candidates[1].appearance = &rival.blue;
  rival.detections[0].appearance = rival.blue;
  EXPECT_EQ(rival.matched(config), (std::map<int, int>{{1, 0}}));
}

TEST(Appearance, WithRivalAlikeTheContestedGateRefusesOnlyWhereARivalLooksLikeTheDetection) {
  TrackerConfig config;
  config.appearance_gate = 0.8;
  config.appearance_gate_contested = true;
  config.appearance_gate_rival_alike = true;
  // One detection in colours neither red track wore, both tracks' boxes allow it: no rival looks
  // alike, so the colours cannot tell the tracks apart and the better box takes it (the plain
  // contested gate refuses both).
  SideBySide unlike(true);
  unlike.candidates[1].appearance = &unlike.red;
  unlike.one_detection_on_the_first_track(colour(12));
  EXPECT_EQ(unlike.matched(config), (std::map<int, int>{{0, 0}}));
  config.appearance_gate_rival_alike = false;
  EXPECT_TRUE(unlike.matched(config).empty());
  config.appearance_gate_rival_alike = true;

  // A rival without a model says nothing either: the track whose box fits keeps its person,
  // however their colours changed.
  SideBySide modelless(true);
  modelless.candidates[1].appearance = nullptr;
  modelless.one_detection_on_the_first_track(colour(12));
  EXPECT_EQ(modelless.matched(config), (std::map<int, int>{{0, 0}}));

  // The blue track looks like the detection: the red one, beyond the gate, is refused, and the
  // detection goes to blue though its box fits red better.
  SideBySide alike(true);
  alike.one_detection_on_the_first_track(alike.blue);
  EXPECT_EQ(alike.matched(config), (std::map<int, int>{{1, 0}}));

  // Two people crossing, all four pairs possible: each detection's own track looks alike, so the
  // gate refuses the crossed pairs as the contested gate does.
  EXPECT_EQ(SideBySide(true).matched(config), (std::map<int, int>{{0, 0}, {1, 1}}));
}

}  // namespace
}  // namespace rtmot::tracker
