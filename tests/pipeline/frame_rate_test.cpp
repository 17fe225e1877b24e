// The one frame-rate computation (pipeline/frame_rate.hpp) every report, log line and gauge uses.
#include "pipeline/frame_rate.hpp"

#include <gtest/gtest.h>

#include <cstdint>

namespace rtmot::pipeline {
namespace {

TEST(FramesPerSecond, CountsFramesOverTheSpan) {
  EXPECT_DOUBLE_EQ(frames_per_second(30, 1'000'000'000), 30.0);
  // 795 frames of vtest.avi sent over 7.95 s.
  EXPECT_DOUBLE_EQ(frames_per_second(795, 7'950'000'000), 100.0);
  // A 1 ms span: the rate, not a truncated count.
  EXPECT_DOUBLE_EQ(frames_per_second(1, 1'000'000), 1000.0);
}

TEST(FramesPerSecond, NothingMeasuredIsZeroNeverADivisionByZero) {
  EXPECT_EQ(frames_per_second(0, 0), 0.0);
  EXPECT_EQ(frames_per_second(12, 0), 0.0);  // one instant: no span yet
  // A clock that never started (first timestamp 0 subtracted the other way): no negative rate.
  EXPECT_EQ(frames_per_second(12, -5'000'000), 0.0);
}

static_assert(frames_per_second(10, 2'000'000'000) == 5.0, "usable in constant expressions");

}  // namespace
}  // namespace rtmot::pipeline
