#include "events/geometry.hpp"

#include <gtest/gtest.h>

namespace rtmot::events {
namespace {

const Segment kVertical{{10.0, 0.0}, {10.0, 100.0}};  // top to bottom: left is +x on the image

TEST(Geometry, SignedDistanceIsNegativeOnTheLeftAsSeenFromTheStart) {
  EXPECT_DOUBLE_EQ(signed_distance(kVertical, {15.0, 50.0}), -5.0);
  EXPECT_DOUBLE_EQ(signed_distance(kVertical, {7.0, 50.0}), 3.0);
  EXPECT_DOUBLE_EQ(signed_distance(kVertical, {10.0, 500.0}), 0.0);
}

TEST(Geometry, CrossingPositionAlongTheLine) {
  double position = -1.0;
  ASSERT_TRUE(crossing_position(kVertical, {0.0, 20.0}, {20.0, 40.0}, position));
  EXPECT_DOUBLE_EQ(position, 0.3);
  ASSERT_TRUE(crossing_position(kVertical, {20.0, 40.0}, {0.0, 20.0}, position));
  EXPECT_DOUBLE_EQ(position, 0.3);
  // Beyond the end: met on the infinite line, outside [0, 1].
  ASSERT_TRUE(crossing_position(kVertical, {0.0, 150.0}, {20.0, 150.0}, position));
  EXPECT_DOUBLE_EQ(position, 1.5);
  EXPECT_FALSE(crossing_position(kVertical, {0.0, 20.0}, {5.0, 40.0}, position));
  EXPECT_FALSE(crossing_position(kVertical, {10.0, 20.0}, {10.0, 40.0}, position));  // along it
  EXPECT_TRUE(crossing_position(kVertical, {0.0, 20.0}, {10.0, 20.0}, position));    // touches
}

TEST(Geometry, SegmentsTouchingAtAnEndIntersect) {
  EXPECT_TRUE(segments_intersect({{0, 0}, {10, 10}}, {{0, 10}, {10, 0}}));
  EXPECT_TRUE(segments_intersect({{0, 0}, {5, 5}}, {{5, 5}, {10, 0}}));
  EXPECT_FALSE(segments_intersect({{0, 0}, {4, 4}}, {{5, 5}, {10, 0}}));
  EXPECT_FALSE(segments_intersect({{0, 0}, {10, 0}}, {{0, 1}, {10, 1}}));
  EXPECT_TRUE(segments_intersect({{0, 0}, {10, 0}}, {{5, 0}, {15, 0}}));  // overlapping
}

// A U shape: the notch between the arms (x 4..6, y 0..8) is outside.
const std::vector<Point> kU{{0, 0}, {4, 0}, {4, 8}, {6, 8}, {6, 0}, {10, 0}, {10, 10}, {0, 10}};

TEST(Geometry, ConcavePolygonInsideAndOutside) {
  EXPECT_TRUE(inside_polygon(kU, {2, 5}));
  EXPECT_TRUE(inside_polygon(kU, {8, 5}));
  EXPECT_TRUE(inside_polygon(kU, {5, 9}));
  EXPECT_FALSE(inside_polygon(kU, {5, 5}));  // in the notch
  EXPECT_FALSE(inside_polygon(kU, {11, 5}));
  EXPECT_DOUBLE_EQ(distance_to_boundary(kU, {5, 5}), 1.0);
  EXPECT_TRUE(move_meets_boundary(kU, {5, 5}, {5, 9}));
  EXPECT_FALSE(move_meets_boundary(kU, {5, 1}, {5, 7}));  // stays in the notch
}

TEST(Geometry, SimplePolygons) {
  EXPECT_TRUE(is_simple_polygon(kU));
  EXPECT_TRUE(is_simple_polygon({{0, 0}, {10, 0}, {0, 10}}));
  EXPECT_FALSE(is_simple_polygon({{0, 0}, {10, 0}}));                     // too few
  EXPECT_FALSE(is_simple_polygon({{0, 0}, {10, 10}, {10, 0}, {0, 10}}));  // a bow tie
  EXPECT_FALSE(is_simple_polygon({{0, 0}, {5, 0}, {10, 0}}));             // no area
  EXPECT_FALSE(is_simple_polygon({{0, 0}, {10, 0}, {10, 0}, {0, 10}}));   // a zero-length edge
  EXPECT_FALSE(is_simple_polygon({{0, 0}, {10, 0}, {5, 0}, {5, 5}}));     // folds back on an edge
}

}  // namespace
}  // namespace rtmot::events
