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

}  // namespace
}  // namespace rtmot
