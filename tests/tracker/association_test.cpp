// One association round: sort.py's one-to-one shortcut, the optimal assignment, the gate.
#include "tracker/association.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "scene.hpp"

namespace rtmot::tracker {
namespace {
using test::detection;
const double kSortIou = TrackerConfig::sort_preset().affinity_threshold;

AssociationCandidate candidate(float x, float y) {
  return AssociationCandidate{Box{x, y, 40.F, 80.F}, 1.0};
}

TEST(Associator, PairsEachDetectionWithItsOnlyOverlappingTrack) {
  Associator associator(4, 4);
  std::vector<AssociationMatch> matches;
  associator.associate(TrackerConfig::sort_preset(), kSortIou,
                       {detection(302.F, 0.F), detection(2.F, 0.F), detection(900.F, 0.F)},
                       {candidate(0.F, 0.F), candidate(300.F, 0.F)}, matches);
  ASSERT_EQ(matches.size(), 2U);
  EXPECT_EQ(matches[0].detection, 0);
  EXPECT_EQ(matches[0].candidate, 1);
  EXPECT_EQ(matches[1].detection, 1);
  EXPECT_EQ(matches[1].candidate, 0);
}

TEST(Associator, ResolvesContestedDetectionsOptimally) {
  // Detection 0 overlaps both tracks equally (IoU 0.6); detection 1 overlaps track 0 well (0.86)
  // and track 1 barely (0.27). Taking track 0 for detection 0 first would leave detection 1
  // without a partner; the optimum pairs detection 1 with track 0 and detection 0 with track 1.
  Associator associator(4, 4);
  std::vector<AssociationMatch> matches;
  associator.associate(TrackerConfig::sort_preset(), kSortIou,
                       {detection(10.F, 0.F), detection(-3.F, 0.F)},
                       {candidate(0.F, 0.F), candidate(20.F, 0.F)}, matches);
  ASSERT_EQ(matches.size(), 2U);
  EXPECT_EQ(matches[0].detection, 0);
  EXPECT_EQ(matches[0].candidate, 1);
  EXPECT_EQ(matches[1].detection, 1);
  EXPECT_EQ(matches[1].candidate, 0);
}

TEST(Associator, DropsAssignedPairsBelowTheThreshold) {
  // Detection 1 fits both tracks (IoU 0.95), so the solver decides. Its optimum gives track 0 to
  // detection 1 and track 1 to detection 0, whose IoU (0.18) is below 0.3: that pair is dropped.
  Associator associator(1, 1);
  std::vector<AssociationMatch> matches;
  associator.associate(TrackerConfig::sort_preset(), kSortIou,
                       {detection(30.F, 0.F), detection(1.F, 0.F)},
                       {candidate(0.F, 0.F), candidate(2.F, 0.F)}, matches);
  ASSERT_EQ(matches.size(), 1U);
  EXPECT_EQ(matches[0].detection, 1);
  EXPECT_EQ(matches[0].candidate, 0);
}

TEST(Associator, EmptyInputsGiveNoMatches) {
  Associator associator(2, 2);
  std::vector<AssociationMatch> matches;
  associator.associate(TrackerConfig::sort_preset(), kSortIou, {}, {candidate(0.F, 0.F)}, matches);
  associator.associate(TrackerConfig::sort_preset(), kSortIou, {detection(0.F, 0.F)}, {}, matches);
  EXPECT_TRUE(matches.empty());
}

}  // namespace
}  // namespace rtmot::tracker
