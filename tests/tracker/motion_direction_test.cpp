// OC-SORT's direction term: a track's way from its own observations, and the assignment's
// preference for the detection lying that way (direction_weight).
#include "tracker/motion_direction.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "scene.hpp"
#include "tracker/association.hpp"

namespace rtmot::tracker {
namespace {
using test::detection;

Box person_at(float x, float y) { return Box{x, y, 40.F, 80.F}; }

// A walker observed at updates 0, 1 and 2, `step` apart each update.
MotionDirection walked(float x, float y, float step_x, float step_y) {
  MotionDirection direction;
  direction.start(person_at(x, y), 0);
  direction.observe(person_at(x + step_x, y + step_y), 1);
  direction.observe(person_at(x + 2 * step_x, y + 2 * step_y), 2);
  return direction;
}

TEST(MotionDirection, ADetectionAheadAgreesBehindDisagreesAsideIsNeutral) {
  const MotionDirection right = walked(0.F, 100.F, 10.F, 0.F);
  ASSERT_TRUE(right.has_direction());
  EXPECT_NEAR(right.agreement(3, person_at(40.F, 100.F)), 0.5, 1e-9);
  EXPECT_NEAR(right.agreement(3, person_at(-30.F, 100.F)), -0.5, 1e-9);
  EXPECT_NEAR(right.agreement(3, person_at(0.F, 140.F)), 0.0, 1e-9);
  // 45 degrees off the way: a quarter.
  EXPECT_NEAR(right.agreement(3, person_at(30.F, 130.F)), 0.25, 1e-6);
}

TEST(MotionDirection, OneObservationGivesNoDirection) {
  MotionDirection direction;
  direction.start(person_at(0.F, 0.F), 0);
  EXPECT_FALSE(direction.has_direction());
  EXPECT_EQ(direction.agreement(1, person_at(50.F, 0.F)), 0.0);
  // A second observation at the same place gives none either: no way is defined.
  direction.observe(person_at(0.F, 0.F), 1);
  EXPECT_FALSE(direction.has_direction());
}

TEST(MotionDirection, TheReferenceIsTheOldestObservationWithinThreeUpdates) {
  MotionDirection direction = walked(0.F, 0.F, 10.F, 0.F);  // updates 0, 1, 2
  EXPECT_FLOAT_EQ(direction.reference(3).x, 0.F);
  EXPECT_FLOAT_EQ(direction.reference(4).x, 10.F);
  // Unseen for a while: the latest observation, as OC-SORT falls back to.
  EXPECT_FLOAT_EQ(direction.reference(9).x, 20.F);
  // A track that turned: from update 3 it walks down; the way spans three updates, so it turns
  // with the walker within them, not at once.
  direction.observe(person_at(20.F, 30.F), 3);
  EXPECT_GT(direction.agreement(4, person_at(50.F, 0.F)), 0.0);
  direction.observe(person_at(20.F, 60.F), 4);
  direction.observe(person_at(20.F, 90.F), 5);
  direction.observe(person_at(20.F, 120.F), 6);
  EXPECT_NEAR(direction.agreement(7, person_at(20.F, 200.F)), 0.5, 1e-9);
}

// Two walkers meet: A walks right, B walks down, and this frame's boxes lie where their
// overlaps (all four pairs possible, IoU 0.32-0.53) prefer the swap by 0.03. The way each has
// been walking tells them apart.
TEST(MotionDirection, TheAssignmentPrefersTheDetectionTheTrackWalksTowards) {
  const MotionDirection a = walked(0.F, 100.F, 10.F, 0.F);
  const MotionDirection b = walked(40.F, 40.F, 0.F, 10.F);
  const std::vector<AssociationCandidate> candidates{
      AssociationCandidate{person_at(30.F, 100.F), 1.0, 0.F, nullptr, &a, 3},
      AssociationCandidate{person_at(40.F, 70.F), 1.0, 0.F, nullptr, &b, 3}};
  const std::vector<Detection> detections{detection(49.F, 100.F), detection(28.F, 78.F)};

  TrackerConfig config = TrackerConfig::sort_preset();
  Associator associator(2, 2);
  std::vector<AssociationMatch> matches;
  associator.associate(config, config.affinity_threshold, detections, candidates, matches);
  ASSERT_EQ(matches.size(), 2U);
  EXPECT_EQ(matches[0].candidate, 1) << "by overlap alone, A's box goes to B";

  config.direction_weight = 0.4;
  matches.clear();
  associator.associate(config, config.affinity_threshold, detections, candidates, matches);
  ASSERT_EQ(matches.size(), 2U);
  EXPECT_EQ(matches[0].detection, 0);
  EXPECT_EQ(matches[0].candidate, 0) << "A walks right, towards the first box";
  EXPECT_EQ(matches[1].candidate, 1);
}

}  // namespace
}  // namespace rtmot::tracker
