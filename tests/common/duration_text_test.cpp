// The remaining time of progress lines.
#include "common/duration_text.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace rtmot {
namespace {

TEST(MinutesSeconds, RoundsToWholeSecondsAsMinutesAndSeconds) {
  EXPECT_EQ(minutes_seconds(0.0), "0:00");
  EXPECT_EQ(minutes_seconds(59.4), "0:59");
  EXPECT_EQ(minutes_seconds(59.5), "1:00");
  EXPECT_EQ(minutes_seconds(125.0), "2:05");
  EXPECT_EQ(minutes_seconds(4500.0), "75:00");
}

TEST(MinutesSeconds, NegativeOrNotFiniteIsZero) {
  EXPECT_EQ(minutes_seconds(-3.0), "0:00");
  EXPECT_EQ(minutes_seconds(std::numeric_limits<double>::quiet_NaN()), "0:00");
  EXPECT_EQ(minutes_seconds(std::numeric_limits<double>::infinity()), "0:00");
}

}  // namespace
}  // namespace rtmot
