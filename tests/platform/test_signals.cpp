#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <thread>

#include "platform/signals.hpp"

namespace rtmot::platform {
namespace {

bool wait_for_stop(const StopSignals& signals) {
  // Bounded wait for the watcher thread; the deadline only keeps a broken build from hanging.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (!signals.stop_requested() && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return signals.stop_requested();
}

class Signals : public testing::TestWithParam<int> {};

TEST_P(Signals, ProcessSignalSetsTheStopFlag) {
  const StopSignals signals;
  EXPECT_FALSE(signals.stop_requested());
  // To the whole process, as `kill` or systemd send it: if it were not caught, the test would die.
  ASSERT_EQ(kill(getpid(), GetParam()), 0);
  ASSERT_TRUE(wait_for_stop(signals));
  EXPECT_EQ(signals.signal_number(), GetParam());
}

INSTANTIATE_TEST_SUITE_P(IntAndTerm, Signals, testing::Values(SIGINT, SIGTERM));

TEST(StopSignalsTest, RequestStopWithoutASignal) {
  StopSignals signals;
  signals.request_stop();
  EXPECT_TRUE(signals.stop_flag().load());
  EXPECT_EQ(signals.signal_number(), 0);
}

TEST(StopSignalsTest, RestoresTheSignalMaskWhenDestroyed) {
  sigset_t before;
  sigset_t during;
  sigset_t after;
  pthread_sigmask(SIG_SETMASK, nullptr, &before);
  {
    const StopSignals signals;
    pthread_sigmask(SIG_SETMASK, nullptr, &during);
  }
  pthread_sigmask(SIG_SETMASK, nullptr, &after);
  EXPECT_FALSE(sigismember(&before, SIGINT));
  EXPECT_TRUE(sigismember(&during, SIGINT));
  EXPECT_TRUE(sigismember(&during, SIGTERM));
  EXPECT_FALSE(sigismember(&after, SIGINT));
  EXPECT_FALSE(sigismember(&after, SIGTERM));
}

TEST(StopSignalsTest, HangupAsksForAReloadAndDoesNotStop) {
  const StopSignals signals(Hangup::reloads);
  EXPECT_EQ(signals.reload_requests(), 0U);
  // To the whole process: with its default action it would end the test.
  ASSERT_EQ(kill(getpid(), SIGHUP), 0);
  EXPECT_EQ(signals.wait_for_reload(0, std::chrono::seconds(10)), 1U);
  ASSERT_EQ(kill(getpid(), SIGHUP), 0);
  EXPECT_EQ(signals.wait_for_reload(1, std::chrono::seconds(10)), 2U);
  EXPECT_FALSE(signals.stop_requested());
  EXPECT_EQ(signals.signal_number(), 0);
}

TEST(StopSignalsTest, WaitingForAReloadEndsAfterItsTimeout) {
  const StopSignals signals(Hangup::reloads);
  EXPECT_EQ(signals.wait_for_reload(0, std::chrono::milliseconds(1)), 0U);
}

TEST(StopSignalsTest, HangupKeepsItsDefaultActionUnlessAsked) {
  // As main() leaves it for every command: blocked from the start.
  sigset_t hangup;
  sigemptyset(&hangup);
  sigaddset(&hangup, SIGHUP);
  sigset_t before;
  pthread_sigmask(SIG_BLOCK, &hangup, &before);
  sigset_t during;
  {
    const StopSignals signals;  // Hangup::ends
    pthread_sigmask(SIG_SETMASK, nullptr, &during);
  }
  pthread_sigmask(SIG_SETMASK, &before, nullptr);
  EXPECT_FALSE(sigismember(&during, SIGHUP)) << "a command that has nothing to re-read";
}

}  // namespace
}  // namespace rtmot::platform
