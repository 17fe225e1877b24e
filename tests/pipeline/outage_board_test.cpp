// The all-sources-down lines (pipeline/outage_board.hpp): one when the last source goes down, one
// every 30 s while all are, one when the first comes back; never for a single source (its own
// lines say it). And under concurrent capture threads: one announcement per episode.
#include "pipeline/outage_board.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <thread>
#include <vector>

namespace rtmot::pipeline {
namespace {

constexpr std::int64_t s = 1'000'000'000;

TEST(OutageBoard, OneLineWhenEverySourceIsDownThenEvery30sThenWhenOneIsBack) {
  OutageBoard board(3);
  EXPECT_FALSE(board.went_down(0 * s));
  EXPECT_FALSE(board.went_down(1 * s));
  EXPECT_FALSE(board.tick(2 * s));  // two of three down: each source's own lines say it
  EXPECT_EQ(board.went_down(5 * s).value_or(""),
            "all 3 sources are down: no pictures to track (each is reopened with backoff; "
            "messages flagged source_outage go on)");
  EXPECT_FALSE(board.tick(34 * s));
  EXPECT_EQ(board.tick(35 * s).value_or(""), "all 3 sources still down after 30 s");
  EXPECT_FALSE(board.tick(35 * s));  // the other capture threads' ticks: printed once
  EXPECT_FALSE(board.tick(64 * s));
  EXPECT_EQ(board.tick(65 * s).value_or(""), "all 3 sources still down after 60 s");
  EXPECT_EQ(board.came_back(70 * s).value_or(""),
            "a source is back after all 3 were down for 65 s");
  EXPECT_FALSE(board.tick(200 * s));  // two still down: no all-down line
  EXPECT_FALSE(board.came_back(201 * s));
  // A second episode starts its own clock.
  EXPECT_FALSE(board.went_down(300 * s));
  EXPECT_TRUE(board.went_down(310 * s));
  EXPECT_FALSE(board.tick(330 * s));
  EXPECT_EQ(board.tick(340 * s).value_or(""), "all 3 sources still down after 30 s");
}

TEST(OutageBoard, ASingleSourceHasNoExtraLines) {
  OutageBoard board(1);
  EXPECT_FALSE(board.went_down(0));
  EXPECT_FALSE(board.tick(100 * s));
  EXPECT_FALSE(board.came_back(101 * s));
}

// Eight capture threads going down and up at once, many times: every episode in which all were
// down is announced exactly once, and the count ends at zero.
TEST(OutageBoard, ConcurrentCaptureThreadsAnnounceEachEpisodeOnce) {
  constexpr int sources = 8;
  constexpr int rounds = 2000;
  OutageBoard board(sources, 1);
  std::atomic<int> announced{0};
  std::atomic<int> back{0};
  std::atomic<int> arrived{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < sources; ++t) {
    threads.emplace_back([&] {
      for (int round = 0; round < rounds; ++round) {
        if (board.went_down(round)) announced.fetch_add(1);
        board.tick(round);
        // Everyone is down before anyone comes back: each round is one all-down episode.
        arrived.fetch_add(1);
        while (arrived.load() < (2 * round + 1) * sources) std::this_thread::yield();
        if (board.came_back(round)) back.fetch_add(1);
        arrived.fetch_add(1);
        while (arrived.load() < (2 * round + 2) * sources) std::this_thread::yield();
      }
    });
  }
  for (auto& thread : threads) thread.join();
  EXPECT_EQ(announced.load(), rounds);
  EXPECT_EQ(back.load(), rounds);
  EXPECT_EQ(board.down(), 0);
}

}  // namespace
}  // namespace rtmot::pipeline
