// XNNPACK's pool or the caller's thread, by measured pass times (detector/pool_governor.hpp): the
// times are given, so the decisions are exact.
#include "detector/pool_governor.hpp"

#include <gtest/gtest.h>

namespace rtmot::detector {
namespace {

constexpr std::int64_t kMs = 1'000'000;

// Runs one pass the way the governor says, taking `pooled` or `alone` ns; returns that way.
bool pass(PoolGovernor& governor, std::int64_t pooled, std::int64_t alone) {
  const bool pool = governor.use_pool();
  governor.record(pool ? pooled : alone);
  return pool;
}

TEST(PoolGovernor, MeasuresBothWaysFirstThenKeepsTheFaster) {
  PoolGovernor governor(8, 64);
  EXPECT_TRUE(pass(governor, 10 * kMs, 20 * kMs));
  EXPECT_FALSE(pass(governor, 10 * kMs, 20 * kMs));
  for (int i = 0; i < 8; ++i) EXPECT_TRUE(pass(governor, 10 * kMs, 20 * kMs)) << i;
  EXPECT_EQ(governor.pooled_ns(), 10 * kMs);
  EXPECT_EQ(governor.inline_ns(), 20 * kMs);
}

TEST(PoolGovernor, LeavesThePoolWhenItCollapsesAndProbesItLessOften) {
  PoolGovernor governor(4, 16);
  pass(governor, 10 * kMs, 20 * kMs);
  pass(governor, 10 * kMs, 20 * kMs);
  // The cores get busy: the pool's passes take 1 s. Its estimate moves a quarter of the way per
  // pass, so the second slow pass already puts it above the caller's thread alone.
  EXPECT_TRUE(pass(governor, 1000 * kMs, 20 * kMs));
  int pooled = 0;
  for (int i = 0; i < 100; ++i) pooled += pass(governor, 1000 * kMs, 20 * kMs) ? 1 : 0;
  // Probes after 4, then 8, then every 16 passes alone: 7 of the 100.
  EXPECT_EQ(pooled, 7);
  EXPECT_EQ(governor.inline_ns(), 20 * kMs);
}

TEST(PoolGovernor, ReturnsToThePoolWhenAProbeWins) {
  PoolGovernor governor(4, 16);
  pass(governor, 1000 * kMs, 20 * kMs);
  EXPECT_FALSE(pass(governor, 1000 * kMs, 20 * kMs));
  for (int i = 0; i < 4; ++i) EXPECT_FALSE(pass(governor, 10 * kMs, 20 * kMs)) << i;
  EXPECT_TRUE(pass(governor, 10 * kMs, 20 * kMs));  // the probe: 10 < 20, switches
  for (int i = 0; i < 4; ++i) EXPECT_TRUE(pass(governor, 10 * kMs, 20 * kMs)) << i;
  EXPECT_EQ(governor.passes(), 11);
  EXPECT_EQ(governor.pooled_passes(), 6);
}

TEST(PoolGovernor, OneSlowPassDoesNotSwitch) {
  PoolGovernor governor(8, 64);
  pass(governor, 10 * kMs, 20 * kMs);
  pass(governor, 10 * kMs, 20 * kMs);
  EXPECT_TRUE(pass(governor, 45 * kMs, 20 * kMs));  // estimate 10 + 35 / 4 = 18.75 ms
  EXPECT_TRUE(pass(governor, 10 * kMs, 20 * kMs));
}

}  // namespace
}  // namespace rtmot::detector
