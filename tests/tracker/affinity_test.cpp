// The three affinities on boxes whose values can be worked out by hand.
#include "tracker/affinity.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rtmot::tracker {
namespace {

TEST(IouAffinity, MatchesHandComputedOverlaps) {
  const Box a{0.F, 0.F, 10.F, 10.F};
  EXPECT_FLOAT_EQ(iou_affinity(a, a), 1.F);
  EXPECT_FLOAT_EQ(iou_affinity(a, Box{5.F, 0.F, 10.F, 10.F}), 50.F / 150.F);
  EXPECT_FLOAT_EQ(iou_affinity(a, Box{5.F, 5.F, 10.F, 10.F}), 25.F / 175.F);
  EXPECT_FLOAT_EQ(iou_affinity(a, Box{10.F, 0.F, 10.F, 10.F}), 0.F);  // touching edges
  EXPECT_FLOAT_EQ(iou_affinity(a, Box{2.F, 2.F, 4.F, 4.F}), 16.F / 100.F);
  EXPECT_FLOAT_EQ(iou_affinity(Box{0.F, 0.F, 0.F, 0.F}, Box{0.F, 0.F, 0.F, 0.F}), 0.F);
}

TEST(LinearAffinity, IsDiagonalOverDistanceTimesAreaOverAreaDifference) {
  const Box track{0.F, 0.F, 10.F, 10.F};      // centre (5, 5), area 100
  const Box detection{3.F, 4.F, 10.F, 12.F};  // centre (8, 10), area 120
  const double expected = (std::hypot(100.0, 50.0) / std::hypot(3.0, 5.0)) * (5000.0 / 20.0);
  EXPECT_NEAR(linear_affinity(track, detection, 100.F, 50.F), expected, expected * 1e-9);
  // Closer and more alike is more similar.
  const Box closer{1.F, 1.F, 10.F, 11.F};
  EXPECT_GT(linear_affinity(track, closer, 100.F, 50.F),
            linear_affinity(track, detection, 100.F, 50.F));
  EXPECT_EQ(linear_affinity(track, track, 100.F, 50.F), kMaxLinearAffinity);
}

TEST(ExponentialAffinity, IsOneForIdenticalBoxesAndFallsAsInYuEtAl) {
  const Box track{0.F, 0.F, 10.F, 20.F};
  EXPECT_DOUBLE_EQ(exponential_affinity(track, track), 1.0);
  // Shifted by one width: exp(-0.5).
  EXPECT_NEAR(exponential_affinity(track, Box{10.F, 0.F, 10.F, 20.F}), std::exp(-0.5), 1e-12);
  // Same centre, twice the height: exp(-1.5 * 20 / 60).
  EXPECT_NEAR(exponential_affinity(track, Box{0.F, -10.F, 10.F, 40.F}), std::exp(-0.5), 1e-12);
}

TEST(Affinity, FollowsTheConfiguredKind) {
  TrackerConfig config;
  const Box a{0.F, 0.F, 10.F, 10.F};
  const Box b{5.F, 0.F, 10.F, 10.F};
  config.affinity = AffinityKind::iou;
  EXPECT_FLOAT_EQ(static_cast<float>(affinity(config, a, b, 1.0)), 50.F / 150.F);
  config.affinity = AffinityKind::exponential;
  EXPECT_DOUBLE_EQ(affinity(config, a, b, 1.0), exponential_affinity(a, b));
  config.affinity = AffinityKind::linear;
  EXPECT_DOUBLE_EQ(affinity(config, a, b, 1.0),
                   linear_affinity(a, b, config.image_width, config.image_height));
}

TEST(Affinity, WidenedGateLoosensOnlyAfterAMissedFrame) {
  TrackerConfig config;
  config.time_widened_gate = true;
  const Box a{0.F, 0.F, 40.F, 40.F};
  const Box b{30.F, 0.F, 40.F, 40.F};
  const double plain = iou_affinity(a, b);
  EXPECT_DOUBLE_EQ(affinity(config, a, b, 1.0), plain);  // matched last frame: unchanged
  const double lost_two = affinity(config, a, b, 3.0);
  const double lost_four = affinity(config, a, b, 5.0);
  EXPECT_GT(lost_two, plain);
  EXPECT_GT(lost_four, lost_two);
  EXPECT_FLOAT_EQ(widened_gate_margin(100.0, config.max_gate_margin),
                  widened_gate_margin(1000.0, config.max_gate_margin));  // bounded
  config.max_gate_margin = 0.3;  // a lower cap: lost long, the gate stays tighter
  const double capped = affinity(config, a, b, 100.0);
  EXPECT_GT(capped, plain);
  config.max_gate_margin = 0.6;
  EXPECT_LT(capped, affinity(config, a, b, 100.0));
}

}  // namespace
}  // namespace rtmot::tracker
