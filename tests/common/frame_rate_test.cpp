// One range for every frame rate, and the one index-to-timestamp conversion, which cannot overflow.
#include "common/frame_rate.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>

namespace rtmot {
namespace {

TEST(FrameRate, AbsurdPositiveRatesAreNotRates) {
  EXPECT_TRUE(is_frame_rate(30.0));
  EXPECT_TRUE(is_frame_rate(kMinFrameRate));
  EXPECT_TRUE(is_frame_rate(kMaxFrameRate));
  EXPECT_FALSE(is_frame_rate(1e-300));
  EXPECT_FALSE(is_frame_rate(0.001));
  EXPECT_FALSE(is_frame_rate(0.0));
  EXPECT_FALSE(is_frame_rate(1000.5));
  EXPECT_FALSE(is_frame_rate(std::numeric_limits<double>::quiet_NaN()));
  EXPECT_FALSE(is_frame_rate(std::numeric_limits<double>::infinity()));
}

TEST(FrameRate, TimestampsAreExactAndSaturate) {
  EXPECT_EQ(frame_time_ns(0, 25.0), 0);
  EXPECT_EQ(frame_time_ns(1, 25.0), 40'000'000);
  EXPECT_EQ(frame_time_ns(3, 30.0), 100'000'000);
  // The largest frame index at the slowest rate: 10^12 frames * 100 s is beyond int64 nanoseconds.
  EXPECT_EQ(frame_time_ns(1'000'000'000'000, kMinFrameRate),
            std::numeric_limits<std::int64_t>::max());
  // Even for a rate that should have been refused (llround(inf) was undefined).
  EXPECT_EQ(frame_time_ns(5, 1e-300), std::numeric_limits<std::int64_t>::max());
  EXPECT_EQ(frame_time_ns(-1, 25.0), 0);
}

// The one measured rate every report, log line and gauge divides with.
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
}  // namespace rtmot
