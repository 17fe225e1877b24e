#pragma once
// Gives every thread of OpenCV's pool a task before an allocation count starts.
//
// A pool thread allocates its per-thread state (cv::theRNG()'s TLS slot, set up by OpenCV's
// parallel_for_ wrapper) the first time it runs a task, which is the scheduler's choice: on a
// loaded 2-core CI machine the pinned OpenCV 4.10's one worker first ran a cv::resize stripe in
// the fourth counted frame and added one allocation there, once. That thread had allocated
// before (at its start), so "a thread's first allocation ever" does not catch it; running a task
// on every pool thread beforehand does.
#include <algorithm>
#include <array>
#include <chrono>
#include <mutex>
#include <opencv2/core.hpp>
#include <thread>

namespace rtmot::test {

/// Runs parallel_for_ stripes until every one of cv::getNumThreads() threads ran one (each stripe
/// sleeps briefly, so an idle worker wakes up and takes some). False if some thread never did.
inline bool run_a_task_on_every_opencv_pool_thread() {
  const int wanted = std::max(1, cv::getNumThreads());
  constexpr int kMostThreads = 256;
  std::array<std::thread::id, kMostThreads> seen{};
  int distinct = 0;
  std::mutex mutex;  // the test's set-up, not a hot path
  for (int round = 0; round < 50 && distinct < std::min(wanted, kMostThreads); ++round) {
    cv::parallel_for_(cv::Range(0, 8 * wanted), [&](const cv::Range& stripes) {
      for (int s = stripes.start; s < stripes.end; ++s) {
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
        const std::lock_guard<std::mutex> lock(mutex);
        const auto self = std::this_thread::get_id();
        if (std::find(seen.begin(), seen.begin() + distinct, self) == seen.begin() + distinct &&
            distinct < kMostThreads) {
          seen[static_cast<std::size_t>(distinct++)] = self;
        }
      }
    });
  }
  return distinct >= std::min(wanted, kMostThreads);
}

}  // namespace rtmot::test
