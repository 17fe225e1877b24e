// The grid the counter reads to know which shapes a track can be near: its bounds must be true
// bounds (the counter skips what they rule out), checked at many points against the exact
// distances of geometry.hpp.
#include "events/shape_grid.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace rtmot::events {
namespace {

EventsConfig slanted_lines_and_concave_zones() {
  EventsConfig config;
  config.lines.push_back({"steep", {{300, 0}, {350, 720}}, true});
  config.lines.push_back({"short", {{600, 300}, {700, 340}}, true});  // its sides reach far
  config.zones.push_back({"u",
                          {{800, 100},
                           {860, 100},
                           {860, 250},
                           {920, 250},
                           {920, 100},
                           {980, 100},
                           {980, 300},
                           {800, 300}},
                          0.0});
  config.zones.push_back({"triangle", {{100, 500}, {250, 650}, {50, 700}}, 0.0});
  return config;
}

TEST(ShapeGrid, ShapesNotAmongACellsCandidatesAreAtLeastItsClearanceAway) {
  const EventsConfig config = slanted_lines_and_concave_zones();
  const ShapeGrid grid(config);
  ASSERT_TRUE(grid.enabled());
  std::mt19937 random(3);
  std::uniform_real_distribution<double> x(-100.0, 1200.0);
  std::uniform_real_distribution<double> y(-100.0, 900.0);
  int looked = 0;
  int ruled_out = 0;
  for (int i = 0; i < 20000; ++i) {
    const Point p{x(random), y(random)};
    const std::uint32_t cell = grid.cell_of(p);
    if (cell == ShapeGrid::kOutside) continue;
    ++looked;
    const ShapeGrid::Cell& near = grid.cell(cell);
    for (std::size_t k = 0; k < 4; ++k) {
      if ((near.candidates >> k & 1U) != 0) continue;
      ++ruled_out;
      const double exact = k < 2 ? std::abs(signed_distance(config.lines[k].segment, p))
                                 : distance_to_boundary(config.zones[k - 2].polygon, p);
      ASSERT_GE(exact, near.clearance) << "shape " << k << " at " << p.x << ", " << p.y;
    }
  }
  EXPECT_GT(looked, 10000);  // the grid covers the shapes and a margin (about 60 % of these)
  EXPECT_GT(ruled_out, 30000);
}

TEST(ShapeGrid, OffBeyondItsShapesAndWithMoreShapesThanBits) {
  const ShapeGrid grid(slanted_lines_and_concave_zones());
  EXPECT_EQ(grid.cell_of({-5000.0, 0.0}), ShapeGrid::kOutside);
  for (const Point& corner : {Point{50, 0}, Point{980, 0}, Point{50, 720}, Point{980, 720}})
    EXPECT_NE(grid.cell_of(corner), ShapeGrid::kOutside);  // the shapes' box
  EXPECT_EQ(grid.cell_of({NAN, 300.0}), ShapeGrid::kOutside);
  EventsConfig many;
  for (int i = 0; i <= static_cast<int>(ShapeGrid::kMaxShapes); ++i)
    many.lines.push_back({"l" + std::to_string(i), {{10.0 * i, 0}, {10.0 * i, 100}}, true});
  EXPECT_FALSE(ShapeGrid(many).enabled());
  EXPECT_FALSE(ShapeGrid(EventsConfig{}).enabled());
}

}  // namespace
}  // namespace rtmot::events
